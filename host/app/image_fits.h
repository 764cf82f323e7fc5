// Whether the image the options ask for fits the machine, checked before anything is
// allocated for it (memory_estimate.h), so that an absurd size fails at once with a
// one-line RenderError (gridrt --width 65536 --height 65536) instead of part way.
#pragma once
#include "cl_runtime.h"
#include "options.h"

namespace gridrt {

// The host's physical memory; checked before the scene is loaded or a device opened.
void checkImageFitsHost(const Options& o);

// The device's global memory.
void checkImageFitsDevice(const Options& o, const DeviceInfo& device);

}  // namespace gridrt
