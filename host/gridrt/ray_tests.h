// The `tests` diagnostic of a ray: the ray-triangle tests of its PEs up to and including
// the one that won, in the order the ray enters their voxels (every PE it pierces when it
// misses): what the paper's interrupt chain leaves to test when a ray's PEs run in its
// list's order. It depends on the rays and the structure alone, never on the order the
// device happened to run its work-groups in, so the `tests` AOV is the same from run to run.
#pragma once
#include <vector>

#include "gridrt_types.h"
#include "traversal_lists.h"
#include "uniform_grid.h"

namespace gridrt {

// From a traversal list (nearest first): the PEs' triangles up to the entry of
// `winning_pe` (-1: the whole list).
int testsToWinnerInList(const UniformGrid& grid, const ListEntry* entries, int length,
                        int winning_pe);

// Where `ray` enters PE `pe`'s voxel (UniformGrid::voxelBoxOfPe), in double precision: the
// order of a traversal list for paths that build none (the ray bundles).
double voxelEntryOf(const UniformGrid& grid, const GrRay& ray, int pe);

// A PE a ray pierced, as the ray bundles report them.
struct PiercedPe {
  int ray;
  int pe;
};

// Adds to tests[pair.ray] the triangles of each pierced PE whose voxel the ray enters no
// later than its winner's (every pierced PE where winning_pe[ray] is -1).
void addTestsToWinner(const UniformGrid& grid, const std::vector<GrRay>& rays,
                      const std::vector<PiercedPe>& pairs, const std::vector<int>& winning_pe,
                      std::vector<int>& tests);

}  // namespace gridrt
