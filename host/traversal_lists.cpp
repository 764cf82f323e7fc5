#include "traversal_lists.h"

#include <omp.h>

#include <cstring>

#include "grid_dda.h"

namespace gridrt {

void computeTraversalLists(const UniformGrid& grid, const GrRay* rays, size_t count,
                           TraversalLists& lists) {
  int threads = omp_get_max_threads();
  lists.scratch.resize(threads);
  lists.begin.resize(count + 1);
  lists.begin[0] = 0;
  std::vector<size_t> chunk_first(threads + 1);
  for (int t = 0; t <= threads; ++t) chunk_first[t] = count * t / threads;
#pragma omp parallel num_threads(threads)
  {
    int t = omp_get_thread_num();
    auto& out = lists.scratch[t];
    out.clear();
    const GrGridInfo& g = grid.info;
    for (size_t r = chunk_first[t]; r < chunk_first[t + 1]; ++r) {
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
#pragma omp parallel num_threads(threads)
  {
    int t = omp_get_thread_num();
    const auto& out = lists.scratch[t];
    if (!out.empty())
      std::memcpy(&lists.entries[lists.begin[chunk_first[t]]], out.data(),
                  out.size() * sizeof(ListEntry));
  }
}

}  // namespace gridrt
