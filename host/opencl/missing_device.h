// Why no OpenCL device answered, in one line a user can act on: no driver installed, or
// PoCL unable to make its kernel cache folder (it then reports no device at all, and says
// why only under POCL_DEBUG), or a driver that reported nothing for another reason.
#pragma once
#include <string>

namespace gridrt {

// "no OpenCL platform found" or "no OpenCL device found on any platform", followed by the
// likeliest cause and what to do. `platforms` is how many platforms answered.
std::string missingDeviceMessage(size_t platforms);

// PoCL's cache folder: $POCL_CACHE_DIR, else $XDG_CACHE_HOME/pocl, else ~/.cache/pocl.
std::string poclCacheDir();

}  // namespace gridrt
