// The 3D-DDA of kernels/shared/grid_dda.h for 16 rays at once, one per AVX-512 lane, for
// the traversal lists. Every lane does what gr_dda_begin and gr_dda_step do for its ray,
// operation for operation in the same order and with the same comparisons, so the voxels
// and their intervals are the scalar walk's bit for bit (TraversalLists tests compare
// them). The scalar walk branches on the axis to step at every voxel, a branch the CPU
// mispredicts about every other time; the lanes select it with masks instead.
#pragma once
#include "gridrt_types.h"
#include "traversal_lists.h"

namespace gridrt {

// True where the build targets AVX-512 (F): computeTraversalLists walks 16 rays at once.
#ifdef __AVX512F__
constexpr bool kDdaPacketAvailable = true;
#else
constexpr bool kDdaPacketAvailable = false;
#endif

// Walks rays[0..count) (count <= 16) through grid g and keeps the voxels whose PE
// (pe_of_voxel, -1 when empty) is not empty: ray k's entries, nearest first, go to
// out[k * stride ...], their number to counts[k]. stride must be at least nx + ny + nz,
// more than the voxels one ray can visit. Without AVX-512 it must not be called.
void ddaPacket16(const GrGridInfo& g, const int* pe_of_voxel, const GrRay* rays, int count,
                 ListEntry* out, int stride, int* counts);

}  // namespace gridrt
