// Binning of the traversal lists by PE: every (ray, PE) pair goes to its PE's bin, and
// within the bin to the part for its direction's octant (the signs of dx, dy, dz), each
// part in ray order: the kernels take a bin's rays 16 at a time, and rays that point
// alike make packets that segment culling serves well (a glass surface spawns an inward
// and an outward ray per hit, side by side in ray order). Each part starts a new packet
// and is cut into tasks of at most `task_rays` pairs, one OpenCL work-group each. The
// pairs are written as packet planes (GR_PAIR_*, gridrt_types.h) carrying their ray, so
// the kernel reads whole packets instead of gathering rays.
#pragma once
#include <cstddef>
#include <vector>

#include "gridrt_types.h"
#include "traversal_lists.h"

namespace gridrt {

struct PeBins {
  std::vector<float> pairs;  // the packet planes (unless binByPe was given `out`)
  size_t packets = 0;        // packets written, padding included
  std::vector<GrPeTask> tasks;
  std::vector<int> pairs_per_pe;                // rays each PE received in the last batch
  std::vector<int> pairs_per_part;              // ... per (PE, octant): index pe * 8 + octant
  std::vector<std::vector<int>> thread_counts;  // scratch reused between batches
};

// Floats of one packet: GR_PAIR_PLANES planes of GR_PACKET_LANES lanes.
constexpr size_t kPairPacketFloats = size_t(GR_PAIR_PLANES) * GR_PACKET_LANES;

// The most packets binByPe writes for `pairs` pairs among `pe_count` PEs (each non-empty
// part pads its last packet).
size_t maxPairPackets(size_t pairs, int pe_count);

// The packets go to `out` (room for maxPairPackets packets) when given, else to
// bins.pairs (resized). task_rays is a multiple of 16.
void binByPe(const TraversalLists& lists, const GrRay* rays, int pe_count, int task_rays,
             PeBins& bins, float* out = nullptr);

}  // namespace gridrt
