// A prefix sum on all cores: each slice sums its part, the slices' sums are added up in
// slice order, then each slice adds its part up from its offset. The same values as the
// one-thread loop (integer sums), whatever the slice count.
#pragma once
#include <cstddef>
#include <vector>

#include "parallel_loops.h"

namespace gridrt {

// values[i] becomes values[0] + ... + values[i], for i in [0, n).
template <typename T>
void inclusiveScan(T* values, size_t n) {
  const int slices = parallelSliceCount();
  // Below this many values a slice's fork costs more than the loop.
  constexpr size_t kMinParallelValues = size_t(1) << 14;
  if (slices <= 1 || n < kMinParallelValues) {
    for (size_t i = 1; i < n; ++i) values[i] += values[i - 1];
    return;
  }
  std::vector<T> sums(size_t(slices), T(0));
  parallelSlices(slices, [&](int me, int count) {
    const auto [first, last] = sliceRange(n, me, count);
    T sum(0);
    for (size_t i = first; i < last; ++i) sum += values[i];
    sums[me] = sum;
  });
  T offset(0);
  for (T& sum : sums) {
    const T part = sum;
    sum = offset;
    offset += part;
  }
  parallelSlices(slices, [&](int me, int count) {
    const auto [first, last] = sliceRange(n, me, count);
    T running = sums[me];
    for (size_t i = first; i < last; ++i) values[i] = running += values[i];
  });
}

}  // namespace gridrt
