#include "ray_bundles.h"

#include <algorithm>

namespace gridrt {

void RayBundles::addRange(int pe, int first, int count, int cull_set) {
  constexpr int kMaxTaskRays = kMaxTaskPackets * GR_PACKET_LANES;
  for (int k = 0; k < count; k += kMaxTaskRays) {
    int n = std::min(kMaxTaskRays, count - k);
    const size_t lanes = size_t(n + GR_PACKET_LANES - 1) / GR_PACKET_LANES * GR_PACKET_LANES;
    // A task that would take its chunk past the limit starts the next chunk.
    const size_t limit = std::min(max_chunk_lanes, kMaxChunkLanes);
    if (chunk_lanes.back() > 0 && chunk_lanes.back() + lanes > limit) {
      chunk_begin.push_back(tasks.size());
      chunk_lanes.push_back(0);
    }
    tasks.push_back(GrBundleTask{pe, first + k, n, int(chunk_lanes.back()), cull_set});
    chunk_lanes.back() += lanes;
    chunk_begin.back() = tasks.size();
    out_lanes += lanes;
  }
}

}  // namespace gridrt
