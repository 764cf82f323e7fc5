#include "ray_bundles.h"

#include <algorithm>
#include <climits>

#include "errors.h"

namespace gridrt {

void RayBundles::addRange(int pe, int first, int count) {
  constexpr int kMaxTaskRays = kMaxTaskPackets * GR_PACKET_LANES;
  for (int k = 0; k < count; k += kMaxTaskRays) {
    int n = std::min(kMaxTaskRays, count - k);
    // Result lanes are indexed with int on the device.
    if (out_lanes + size_t(n) + GR_PACKET_LANES > size_t(INT_MAX))
      throw RenderError(
          "a batch needs more than 2^31 (ray, PE) result lanes; use a coarser --grid or a smaller "
          "image");
    tasks.push_back(GrBundleTask{pe, first + k, n, int(out_lanes)});
    out_lanes += size_t(n + GR_PACKET_LANES - 1) / GR_PACKET_LANES * GR_PACKET_LANES;
  }
}

}  // namespace gridrt
