// A step that talks to the device, with its OpenCL errors said in the user's terms.
#pragma once
#include <string>

#include "cl_runtime.h"
#include "errors.h"

namespace gridrt {

// Runs `step`, turning an OpenCL error into a RenderError that says what was being done
// (main() would otherwise only know the failing OpenCL call), with a hint for the errors
// that mean "too big for this device".
template <class Step>
auto during(const std::string& what, Step&& step) -> decltype(step()) {
  try {
    return step();
  } catch (const cl::Error& e) {
    std::string message =
        "OpenCL error while " + what + ": " + e.what() + " returned " + clErrorName(e.err());
    if (e.err() == CL_OUT_OF_RESOURCES || e.err() == CL_OUT_OF_HOST_MEMORY ||
        e.err() == CL_MEM_OBJECT_ALLOCATION_FAILURE || e.err() == CL_INVALID_BUFFER_SIZE)
      message +=
          " (the device ran out of memory or resources: try a smaller image, fewer "
          "--spp or a coarser --grid)";
    throw RenderError(message);
  }
}

}  // namespace gridrt
