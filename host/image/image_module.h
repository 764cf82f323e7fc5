// The image module (image_codec.h), loaded with dlopen on first use and kept for the life
// of the process. It is looked for beside the running executable (a relocated gridrt
// carries it along), in the installed tree's module folder, then where the build put it
// (module_search.h).
#pragma once
#include "image_codec.h"

namespace gridrt {

// Loads the module the first time; throws RenderError naming the file when it cannot.
const ImageCodec& imageCodec();

}  // namespace gridrt
