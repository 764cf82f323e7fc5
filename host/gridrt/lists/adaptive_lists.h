// Traversal lists over the adaptive structure (adaptive_grid.h): per ray its leaves (PEs)
// nearest first, each with the ray's entry and exit distance. The top grid is walked with
// the 3D-DDA of the uniform grid (grid_dda.h); a cell with a grid below it is walked the
// same way between its entry and exit, with that grid's stored planes, recursively. As in
// the DDA, every boundary distance is computed from a plane ((p - o) * (1/d)), consecutive
// entries share their boundary exactly and cover the ray's whole interval in the grid; a
// merged leaf met in consecutive cells is one entry.
#pragma once
#include <vector>

#include "traversal_lists.h"

namespace gridrt {

// Appends the list of `ray` to `out` (the entries of earlier rays stay as they are).
void adaptiveList(const UniformGrid& grid, const GrRay& ray, std::vector<ListEntry>& out);

// computeTraversalLists for a grid with adaptive cells. Runs on all cores.
void computeAdaptiveLists(const UniformGrid& grid, const GrRay* rays, size_t count,
                          TraversalLists& lists);

}  // namespace gridrt
