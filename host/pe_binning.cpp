#include "pe_binning.h"

#include <omp.h>

#include <algorithm>

namespace gridrt {

namespace {

constexpr int kOctants = 8;

// 0..7 from the signs of the direction (a zero counts as positive).
int octantOf(const GrRay& ray) {
  return (ray.dx < 0.0f ? 1 : 0) | (ray.dy < 0.0f ? 2 : 0) | (ray.dz < 0.0f ? 4 : 0);
}

}  // namespace

void binByPe(const TraversalLists& lists, const GrRay* rays, int pe_count, int task_rays,
             PeBins& bins, GrPeEntry* out) {
  const int threads = omp_get_max_threads();
  const size_t ray_count = lists.rayCount();
  const int parts = pe_count * kOctants;
  bins.thread_counts.resize(threads);
  if (!out) {
    bins.entries.resize(lists.entries.size());
    out = bins.entries.data();
  }
#pragma omp parallel num_threads(threads)
  {
    int t = omp_get_thread_num();
    auto& counts = bins.thread_counts[t];
    counts.assign(parts, 0);
    size_t first = ray_count * t / threads, last = ray_count * (t + 1) / threads;
    for (size_t r = first; r < last; ++r) {
      const int octant = octantOf(rays[r]);
      for (int e = lists.begin[r]; e < lists.begin[r + 1]; ++e)
        ++counts[lists.entries[e].pe * kOctants + octant];
    }
#pragma omp barrier
#pragma omp single
    {
      // Exclusive prefix over (part, thread): thread t's pairs of a part follow thread t-1's.
      bins.pairs_per_part.assign(parts, 0);
      int offset = 0;
      for (int part = 0; part < parts; ++part)
        for (int k = 0; k < threads; ++k) {
          int c = bins.thread_counts[k][part];
          bins.thread_counts[k][part] = offset;
          offset += c;
          bins.pairs_per_part[part] += c;
        }
    }
    for (size_t r = first; r < last; ++r) {
      const int octant = octantOf(rays[r]);
      for (int e = lists.begin[r]; e < lists.begin[r + 1]; ++e) {
        const ListEntry& le = lists.entries[e];
        out[counts[le.pe * kOctants + octant]++] = GrPeEntry{int(r), e, le.t_enter, le.t_exit};
      }
    }
  }
  bins.tasks.clear();
  bins.pairs_per_pe.assign(pe_count, 0);
  int start = 0;
  for (int part = 0; part < parts; ++part) {
    const int pe = part / kOctants, n = bins.pairs_per_part[part];
    bins.pairs_per_pe[pe] += n;
    for (int k = 0; k < n; k += task_rays)
      bins.tasks.push_back(GrPeTask{pe, start + k, std::min(task_rays, n - k), 0});
    start += n;
  }
}

}  // namespace gridrt
