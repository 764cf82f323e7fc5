// The 3D-DDA of kernels/common/grid_dda.h for a packet of rays at once, one per vector
// lane, for the traversal lists. Every lane does what gr_dda_begin and gr_dda_step do for
// its ray, operation for operation in the same order and with the same comparisons, so the
// voxels and their intervals are the scalar walk's bit for bit (TraversalLists tests
// compare them). The scalar walk branches on the axis to step at every voxel, a branch
// the CPU mispredicts about every other time; the lanes select it with masks instead. The
// walk is written once over Highway's vectors and built for the widths the target's
// vectors hold; its packet width depends on the CPU, not on the kernels' packets.
#pragma once
#include "gridrt_types.h"
#include "traversal_lists.h"

namespace gridrt {

// The widest packet any build walks.
constexpr int kDdaPacketMaxLanes = 16;

// The rays ddaPacket walks at once: the widest built width (16 where the build targets
// AVX-512, 8 with AVX2, 4 with other 128-bit vectors); without a vector unit,
// kDdaPacketMaxLanes rays walked one after another by the scalar walk of grid_dda.h.
int ddaPacketLanes();

// Whether the walk of `lanes` lanes (1, 4, 8 or 16) is built for this target.
bool ddaPacketWidthIsBuilt(int lanes);

// Walks rays[0..count) (count <= ddaPacketLanes()) through grid g and keeps the voxels
// whose code (pe_of_voxel: -1 when empty, else a PE, or for the adaptive structure's top
// grid a node below it, AdaptiveCells::top) is not -1: ray k's entries, nearest first, go
// to out[k * stride ...], their number to counts[k]. stride must be at least
// nx + ny + nz, more than the voxels one ray can visit, and out must hold
// ddaPacketLanes() * stride entries.
void ddaPacket(const GrGridInfo& g, const int* pe_of_voxel, const GrRay* rays, int count,
               ListEntry* out, int stride, int* counts);

// The same walk `lanes` rays at a time (ddaPacketWidthIsBuilt(lanes), count <= lanes, out
// holding lanes * stride entries), for the tests of every width.
void ddaPacketOfWidth(int lanes, const GrGridInfo& g, const int* pe_of_voxel, const GrRay* rays,
                      int count, ListEntry* out, int stride, int* counts);

}  // namespace gridrt
