// The 3D-DDA of kernels/common/grid_dda.h for a packet of rays at once, one per vector
// lane (16 with AVX-512, 8 with AVX2), for the traversal lists. Every lane does what
// gr_dda_begin and gr_dda_step do for its ray, operation for operation in the same order
// and with the same comparisons, so the voxels and their intervals are the scalar walk's
// bit for bit (TraversalLists tests compare them). The scalar walk branches on the axis
// to step at every voxel, a branch the CPU mispredicts about every other time; the lanes
// select it with masks instead.
#pragma once
#include "gridrt_types.h"
#include "traversal_lists.h"

namespace gridrt {

// The rays computeTraversalLists walks at once: 16 where the build targets AVX-512 (F), 8
// where it targets AVX2, 0 (the scalar walk) elsewhere. The 8-lane walk against the
// scalar one on an AMD EPYC (AVX2), alternated: default Whitted frame lists 21.4 -> 15.0
// ms, frame 109.6 -> 99.4 ms (9 rounds).
#if defined(__AVX512F__)
constexpr int kDdaPacketLanes = 16;
#elif defined(__AVX2__)
constexpr int kDdaPacketLanes = 8;
#else
constexpr int kDdaPacketLanes = 0;
#endif

// Walks rays[0..count) (count <= kDdaPacketLanes) through grid g and keeps the voxels
// whose PE (pe_of_voxel, -1 when empty) is not empty: ray k's entries, nearest first, go
// to out[k * stride ...], their number to counts[k]. stride must be at least
// nx + ny + nz, more than the voxels one ray can visit. With kDdaPacketLanes 0 it must
// not be called.
void ddaPacket(const GrGridInfo& g, const int* pe_of_voxel, const GrRay* rays, int count,
               ListEntry* out, int stride, int* counts);

}  // namespace gridrt
