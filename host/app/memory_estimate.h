// The memory a render needs, estimated before anything is allocated, so that an image
// that cannot fit is refused at once with a one-line error instead of failing part way.
// A frame is rendered in passes (renderer.h, kMaxPassRays): the film's own arrays grow
// with its pixels (the crop window's, with --crop), the wavefront's only with the samples
// of one pass.
#pragma once

#include "pixel_window.h"

namespace gridrt {

struct MemoryEstimate {
  double pass_samples = 0;  // primary samples of the largest pass
  double host_bytes = 0;    // the frame's arrays and one pass's wavefront
  double device_bytes = 0;  // one pass's rays and results
};

// A width x height image, or with `crop` its window alone (the film holds the window's
// pixels); `full_size_output` places a cropped film in a full-size image to write it
// (--crop-output full), which costs the full image's pixels once more. `batches_copied`
// (--transfer copy) keeps host arrays as large as one pass's device buffers, which the host
// then holds once more.
MemoryEstimate estimateMemory(int width, int height, int spp, const PixelWindow& crop = {},
                              bool full_size_output = true, bool batches_copied = false);

}  // namespace gridrt
