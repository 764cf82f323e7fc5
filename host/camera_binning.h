// Binning of pinhole primary rays by PE through screen footprints: for every PE, the
// pixels its voxel's box projects onto are tested (ray/box slab test, the same plane
// distances as the 3D-DDA) and each ray that pierces the voxel becomes a (ray, PE) pair
// with its entry and exit distance. It yields exactly the pairs of the traversal lists,
// already grouped by PE, without walking empty voxels — the DDA's cost on a CPU.
// A ray's list order is the order of its pairs' entry distances.
#pragma once
#include <vector>

#include "gridrt_types.h"
#include "pinhole_view.h"
#include "uniform_grid.h"

namespace gridrt {

// The pairs stay in the buffers of the threads that made them (no concatenation): the
// device buffer holds them one thread after another, thread t's from thread_offset[t];
// a task's slot_base is its thread's offset and an entry's slot its index there.
struct CameraBins {
  std::vector<GrPeTask> tasks;
  std::vector<int> pairs_per_pe;
  std::vector<std::vector<GrPeEntry>> thread_entries;
  std::vector<size_t> thread_offset;
  size_t entry_count = 0;
  // Scratch reused between batches.
  std::vector<std::vector<GrPeTask>> thread_tasks;
  std::vector<float> inv_dir;  // 1/d per ray and axis (0 on a zero axis)

  // The entries of a task, wherever they are kept.
  const GrPeEntry* entriesOf(const GrPeTask& task) const;
};

void binCameraRaysByPe(const UniformGrid& grid, const PinholeView& view, const GrRay* rays,
                       size_t count, int task_rays, CameraBins& bins);

}  // namespace gridrt
