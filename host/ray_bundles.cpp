#include "ray_bundles.h"

#include <algorithm>

namespace gridrt {

void RayBundles::addRange(int pe, int first, int count) {
  constexpr int kMaxTaskRays = kMaxTaskPackets * kBundleLanes;
  for (int k = 0; k < count; k += kMaxTaskRays) {
    int n = std::min(kMaxTaskRays, count - k);
    tasks.push_back(GrBundleTask{pe, first + k, n, int(out_lanes)});
    out_lanes += size_t(n + kBundleLanes - 1) / kBundleLanes * kBundleLanes;
  }
}

}  // namespace gridrt
