// Binning of the traversal lists by PE: every (ray, PE) pair goes to its PE's bin, and
// within the bin to the part for its direction's octant (the signs of dx, dy, dz), each
// part in ray order: the kernels take a bin's rays 16 at a time, and rays that point
// alike make packets that segment culling serves well (a glass surface spawns an inward
// and an outward ray per hit, side by side in ray order). Each part is cut into tasks of
// at most `task_rays` pairs, one OpenCL work-group each.
#pragma once
#include <vector>

#include "gridrt_types.h"
#include "traversal_lists.h"

namespace gridrt {

struct PeBins {
  std::vector<GrPeEntry> entries;  // grouped by PE (unless binByPe was given `out`)
  std::vector<GrPeTask> tasks;
  std::vector<int> pairs_per_pe;   // rays each PE received in the last batch
  std::vector<int> pairs_per_part; // ... per (PE, octant): index pe * 8 + octant
  std::vector<std::vector<int>> thread_counts;  // scratch reused between batches
};

// The entries go to `out` (room for lists.entries.size()) when given, else to
// bins.entries (resized).
void binByPe(const TraversalLists& lists, const GrRay* rays, int pe_count, int task_rays,
             PeBins& bins, GrPeEntry* out = nullptr);

}  // namespace gridrt
