#pragma once
// The build's identity, printed by `gridrt --version` under the version line:
//   build <SHA-256 of the executable's own bytes>
//   kernels <SHA-256 of the OpenCL C sources embedded in it>
// The kernels are embedded in the executable, so the build id covers them too; two
// executables with the same build id are the same file. The farm (tools/gridrt-farm)
// merges only tiles rendered by one build.
#include <string>

namespace gridrt {

// The three lines above (without a final newline). The executable is read through
// /proc/self/exe; when that fails the build line says "unknown" and why.
std::string versionText(const std::string& version);

}  // namespace gridrt
