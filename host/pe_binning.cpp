#include "pe_binning.h"

#include <omp.h>

#include <algorithm>

namespace gridrt {

void binByPe(const TraversalLists& lists, int pe_count, int task_rays, PeBins& bins) {
  const int threads = omp_get_max_threads();
  const size_t rays = lists.rayCount();
  bins.thread_counts.resize(threads);
  bins.entries.resize(lists.entries.size());
#pragma omp parallel num_threads(threads)
  {
    int t = omp_get_thread_num();
    auto& counts = bins.thread_counts[t];
    counts.assign(pe_count, 0);
    size_t first = rays * t / threads, last = rays * (t + 1) / threads;
    for (int e = lists.begin[first]; e < lists.begin[last]; ++e) ++counts[lists.entries[e].pe];
#pragma omp barrier
#pragma omp single
    {
      // Exclusive prefix over (PE, thread): thread t's pairs of a PE follow thread t-1's.
      bins.pairs_per_pe.assign(pe_count, 0);
      int offset = 0;
      for (int pe = 0; pe < pe_count; ++pe)
        for (int k = 0; k < threads; ++k) {
          int c = bins.thread_counts[k][pe];
          bins.thread_counts[k][pe] = offset;
          offset += c;
          bins.pairs_per_pe[pe] += c;
        }
    }
    for (size_t r = first; r < last; ++r)
      for (int e = lists.begin[r]; e < lists.begin[r + 1]; ++e) {
        const ListEntry& le = lists.entries[e];
        bins.entries[counts[le.pe]++] = GrPeEntry{int(r), e, le.t_enter, le.t_exit};
      }
  }
  bins.tasks.clear();
  int start = 0;
  for (int pe = 0; pe < pe_count; ++pe) {
    int n = bins.pairs_per_pe[pe];
    for (int k = 0; k < n; k += task_rays)
      bins.tasks.push_back(GrPeTask{pe, start + k, std::min(task_rays, n - k), 0});
    start += n;
  }
}

}  // namespace gridrt
