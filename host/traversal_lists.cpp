#include "traversal_lists.h"

#include <algorithm>
#include <cstring>

#include "grid_dda.h"

namespace gridrt {

void computeTraversalLists(const UniformGrid& grid, const GrRay* rays, size_t count,
                           TraversalLists& lists) {
  // Chunks handed out dynamically (list lengths vary a lot across a batch), each with its
  // own output, copied out in chunk order.
  const size_t chunks = (count + kListChunkRays - 1) / kListChunkRays;
  if (lists.scratch.size() < chunks) lists.scratch.resize(chunks);
  lists.begin.resize(count + 1);
  lists.begin[0] = 0;
#pragma omp parallel for schedule(dynamic, 1)
  for (long long chunk = 0; chunk < (long long)chunks; ++chunk) {
    auto& out = lists.scratch[chunk];
    out.clear();
    const GrGridInfo& g = grid.info;
    const size_t last = std::min(count, size_t(chunk + 1) * kListChunkRays);
    for (size_t r = size_t(chunk) * kListChunkRays; r < last; ++r) {
      const GrRay& ray = rays[r];
      size_t before = out.size();
      GrDda s;
      if (gr_dda_begin(&g, ray.ox, ray.oy, ray.oz, ray.dx, ray.dy, ray.dz, ray.tmin, ray.tmax,
                       &s)) {
        do {
          int pe = grid.pe_of_voxel[s.ix + g.nx * (s.iy + g.ny * s.iz)];
          if (pe >= 0) out.push_back({pe, s.t_enter, s.t_exit});
        } while (gr_dda_step(&g, &s));
      }
      lists.begin[r + 1] = int(out.size() - before);  // a count for now
    }
  }
  for (size_t r = 0; r < count; ++r) lists.begin[r + 1] += lists.begin[r];
  lists.entries.resize(lists.begin[count]);
#pragma omp parallel for schedule(static)
  for (long long chunk = 0; chunk < (long long)chunks; ++chunk) {
    const auto& out = lists.scratch[chunk];
    if (!out.empty())
      std::memcpy(&lists.entries[lists.begin[size_t(chunk) * kListChunkRays]], out.data(),
                  out.size() * sizeof(ListEntry));
  }
}

}  // namespace gridrt
