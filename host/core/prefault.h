// Faulting in a large, freshly allocated buffer on every core before it is first written.
// A new buffer of tens of megabytes (the grid's PE triangles) is mapped but not yet
// backed; the first write to each 4 KiB page traps into the kernel, which zeroes it, and
// std::vector's resize makes those writes on one core. Linux's MADV_POPULATE_WRITE (5.14)
// backs a range in one call per slice instead: 50 MB faulted in and zeroed in 30 ms on
// one core, 12 ms on two (2 cores, AMD EPYC, KVM, 2026-12-03). Elsewhere, or on an older
// kernel, nothing happens and the writes fault as before.
#pragma once
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "parallel_loops.h"

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace gridrt {

// Below this a buffer is not worth a parallel loop.
constexpr size_t kPrefaultMinBytes = size_t(1) << 20;

// Backs the whole pages of [data, data + bytes) on all cores; the memory must be allocated
// (a vector's reserved capacity) and its contents are left as they are.
inline void prefaultForWriting(void* data, size_t bytes) {
#if defined(__linux__) && defined(MADV_POPULATE_WRITE)
  if (bytes < kPrefaultMinBytes) return;
  constexpr uintptr_t kPage = 4096;
  const uintptr_t begin = (reinterpret_cast<uintptr_t>(data) + kPage - 1) & ~(kPage - 1);
  const uintptr_t end = (reinterpret_cast<uintptr_t>(data) + bytes) & ~(kPage - 1);
  if (end <= begin) return;
  const size_t pages = (end - begin) / kPage;
  parallelSlices(parallelSliceCount(), [&](int me, int count) {
    const auto [first, last] = sliceRange(pages, me, count);
    if (last > first)
      madvise(reinterpret_cast<void*>(begin + first * kPage), (last - first) * kPage,
              MADV_POPULATE_WRITE);  // a failure (an older kernel) leaves the faults to later
  });
#else
  (void)data;
  (void)bytes;
#endif
}

// Room for n elements in `v`, faulted in on every core, where it has less: for a vector
// about to be filled whole, so its elements are dropped when it grows.
template <typename T, typename Allocator>
void reserveFaultedIn(std::vector<T, Allocator>& v, size_t n) {
  if (n <= v.capacity()) return;
  std::vector<T, Allocator> fresh;
  fresh.reserve(n);
  prefaultForWriting(fresh.data(), n * sizeof(T));
  v.swap(fresh);
}

// Room for `more` elements after v's, faulted in on every core: for a vector about to grow
// by that much (capacity at least doubles, so growing piece by piece stays linear).
template <typename T, typename Allocator>
void reserveMoreFaultedIn(std::vector<T, Allocator>& v, size_t more) {
  if (v.size() + more > v.capacity()) v.reserve(std::max(v.size() + more, 2 * v.capacity()));
  prefaultForWriting(v.data() + v.size(), more * sizeof(T));
}

// v resized to n elements, the room it lacks allocated with headroom and faulted in on
// every core before anything is copied or zeroed into it: for the renderer's per-frame
// arrays, whose first frame otherwise faulted in ~170 MB page by page on one core
// (the default scene at 640x480).
template <typename T, typename Allocator>
void resizeFaultedIn(std::vector<T, Allocator>& v, size_t n) {
  if (n > v.capacity()) {
    std::vector<T, Allocator> fresh;
    fresh.reserve(std::max(n, 2 * v.capacity()));
    prefaultForWriting(fresh.data(), n * sizeof(T));
    fresh.insert(fresh.end(), v.begin(), v.end());
    v.swap(fresh);
  }
  v.resize(n);
}

}  // namespace gridrt
