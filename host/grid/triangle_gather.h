// Reading triangles by position: the grid's loops read a model's triangles through lists
// of positions (a cell's, a PE's), which are increasing but sparse, so each read misses
// the cache unless it is fetched some triangles ahead (the reads were a third of the
// split cells' binning samples on the scattered copies of the bunny, 2026-12-03).
#pragma once
#include <cstddef>

#include "gridrt_types.h"

namespace gridrt {

// How many positions ahead of the triangle being read the next one is fetched.
constexpr size_t kTrianglePrefetchAhead = 16;

// Starts fetching triangle `base[position]` (both cache lines where a triangle straddles
// two: the arrays are not aligned to lines).
inline void prefetchTriangle(const GrTriangle* base, int position) {
  const char* at = reinterpret_cast<const char*>(base + position);
  __builtin_prefetch(at);
  __builtin_prefetch(at + sizeof(GrTriangle) - 1);
}

// out[k] = base[positions[k]] for k in [0, n).
inline void gatherTriangles(const GrTriangle* base, const int* positions, size_t n,
                            GrTriangle* out) {
  for (size_t k = 0; k < n; ++k) {
    if (k + kTrianglePrefetchAhead < n)
      prefetchTriangle(base, positions[k + kTrianglePrefetchAhead]);
    out[k] = base[positions[k]];
  }
}

}  // namespace gridrt
