// The part of each PE's box that its triangles can be hit in: the box cut down to its
// triangles' bounds grown by the grid's margin. The ray bundles (their kernel's in-voxel
// interval, the camera outlines, the light cube) use it in place of the box; the traversal
// lists keep the boxes, which tile the grid.
//
// Why it keeps every hit: a face of the hull that is not a face of the box lies a margin
// beyond every triangle of the PE, so a hit that the margin covers elsewhere (a float t
// that lands just past a voxel boundary, uniform_grid.h) stays inside it too; a face that
// is the box's keeps the box's float bit for bit, shared with the neighbouring PE. A PE
// whose triangles fill its box (most of a model) keeps its box; a floor's or a wall's
// leaves become slabs a margin thick, which most rays over them no longer pierce.
#pragma once
#include <vector>

#include "uniform_grid.h"

namespace gridrt {

// Per PE lo x, y, z then hi x, y, z, as UniformGrid::pe_box; runs on all cores.
std::vector<float> peHulls(const UniformGrid& grid);

}  // namespace gridrt
