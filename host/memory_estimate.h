// The memory a render needs, estimated before anything is allocated, so that an image
// that cannot fit is refused at once with a one-line error instead of failing part way.
// A frame is rendered in passes (renderer.h, kMaxPassRays): the image's own arrays grow
// with its pixels, the wavefront's only with the samples of one pass.
#pragma once

namespace gridrt {

struct MemoryEstimate {
  double pass_samples = 0;  // primary samples of the largest pass
  double host_bytes = 0;    // the frame's arrays and one pass's wavefront
  double device_bytes = 0;  // one pass's rays and results
};

MemoryEstimate estimateMemory(int width, int height, int spp);

}  // namespace gridrt
