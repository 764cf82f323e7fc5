// Traversal lists: for every ray of a batch, the non-empty voxels (PEs) it pierces,
// nearest first, each with the ray's entry and exit distance in that voxel (3D-DDA of
// kernels/common/grid_dda.h). Stored ray-major: the entries of ray r are the slots
// begin[r] .. begin[r+1] - 1, kept in the chunks they were made in (entriesOf).
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

// Rays per chunk of the list computation (a unit of dynamic scheduling).
constexpr size_t kListChunkRays = 2048;

struct TraversalLists {
  std::vector<int> begin;  // ray count + 1
  // The entries of rays [c K, (c + 1) K) (K = kListChunkRays) in chunk c, slots from
  // begin[c K] on: each chunk's lists stay where they were made, never copied into one
  // array (a copy of every batch's entries; docs/history.md, "Traversal lists and DDA
  // packets"). Kept between batches (a batch may use fewer), so nothing is allocated per
  // frame.
  std::vector<std::vector<ListEntry>> chunks;
  std::vector<std::vector<ListEntry>> packet_scratch;  // per thread: 16 rays' lists

  size_t rayCount() const { return begin.empty() ? 0 : begin.size() - 1; }
  int lengthOf(size_t ray) const { return begin[ray + 1] - begin[ray]; }
  size_t entryCount() const { return begin.empty() ? 0 : size_t(begin.back()); }
  // The lengthOf(ray) entries of `ray`, nearest first.
  const ListEntry* entriesOf(size_t ray) const {
    const size_t chunk = ray / kListChunkRays;
    return chunks[chunk].data() + (begin[ray] - begin[chunk * kListChunkRays]);
  }
  // Lists given as one array: ray r's entries at flat[flat_begin[r] .. flat_begin[r + 1]).
  void assign(const std::vector<int>& flat_begin, const std::vector<ListEntry>& flat);
};

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
