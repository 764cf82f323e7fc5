// The viewer's snapshots (the P key): the gridrt command line that renders the picture
// shown, and the file the snapshot goes to.
#pragma once
#include <string>

#include "options.h"

namespace gridrt {

// `gridrt SCENE --width W --height H ...`: the options of `o` that change the picture, in
// the command line's own syntax, numbers written so that they parse back to the same
// floats; the scene path as given (quoted for a POSIX shell where it needs it); no -o.
// Options that give the same image (--device, --threads, --wave-rays, --pe-layout, ...)
// are left out.
std::string commandLineOf(const Options& o);

// SCENE_view_NNNN.png in `folder` ("." for the current one): SCENE the scene file's stem
// ("gridrt" for the built-in scene), NNNN the first number from 0000 whose file does not
// exist yet.
std::string snapshotPath(const Options& o, const std::string& folder = ".");

}  // namespace gridrt
