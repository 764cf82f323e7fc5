// Binning of the traversal lists by PE: every (ray, PE) pair goes to its PE's bin, in ray
// order (coherent rays stay together), and each bin is cut into tasks of at most
// `task_rays` pairs, one OpenCL work-group each.
#pragma once
#include <vector>

#include "gridrt_types.h"
#include "traversal_lists.h"

namespace gridrt {

struct PeBins {
  std::vector<GrPeEntry> entries;  // grouped by PE
  std::vector<GrPeTask> tasks;
  std::vector<int> pairs_per_pe;   // rays each PE received in the last batch
  std::vector<std::vector<int>> thread_counts;  // scratch reused between batches
};

void binByPe(const TraversalLists& lists, int pe_count, int task_rays, PeBins& bins);

}  // namespace gridrt
