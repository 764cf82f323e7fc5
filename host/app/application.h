// The command-line application: options in, image and statistics out. Returns the exit
// code; throws the errors of host/core/errors.h, which main() turns into one-line messages.
#pragma once
#include "options.h"

namespace gridrt {

int runApplication(const Options& options);

}  // namespace gridrt
