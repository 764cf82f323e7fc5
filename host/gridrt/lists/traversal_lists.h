// Traversal lists: for every ray of a batch, the non-empty voxels (PEs) it pierces,
// nearest first, each with the ray's entry and exit distance in that voxel (3D-DDA of
// kernels/common/grid_dda.h). Stored ray-major: the entries of ray r are
// entries[begin[r] .. begin[r+1]), and an entry's index is its "slot".
#pragma once
#include <functional>
#include <vector>

#include "gridrt_types.h"
#include "uniform_grid.h"

namespace gridrt {

struct ListEntry {
  int pe;
  float t_enter;
  float t_exit;
};

struct TraversalLists {
  std::vector<int> begin;          // ray count + 1
  std::vector<ListEntry> entries;  // all rays' lists, ray-major

  size_t rayCount() const { return begin.empty() ? 0 : begin.size() - 1; }
  int lengthOf(size_t ray) const { return begin[ray + 1] - begin[ray]; }

  // Per-chunk scratch, kept between batches so nothing is allocated per frame.
  std::vector<std::vector<ListEntry>> scratch;
  std::vector<std::vector<ListEntry>> packet_scratch;  // per thread: 16 rays' lists
};

// Rays per chunk of the list computation (a unit of dynamic scheduling).
constexpr size_t kListChunkRays = 2048;

// Appends to `out` a ray's entries made from `cells`, its `count` cells of a grid walk.
using ExpandCells = std::function<void(const GrRay& ray, const ListEntry* cells, int count,
                                       std::vector<ListEntry>& out)>;

// Lists made chunk by chunk on all cores: the grid `g` is walked a packet of rays at a time
// (dda_packet.h), keeping the cells whose code (`codes`, per voxel) is not -1, and each
// ray's cells go through `expand`.
void computeListsOverCells(const GrGridInfo& g, const int* codes, const GrRay* rays, size_t count,
                           TraversalLists& lists, const ExpandCells& expand);

// Fills `lists` for rays[0..count). Runs on all cores.
void computeTraversalLists(const UniformGrid& grid, const GrRay* rays, size_t count,
                           TraversalLists& lists);

}  // namespace gridrt
