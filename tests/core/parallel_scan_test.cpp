// inclusiveScan: the one-thread prefix sum's values at every slice count and size,
// across the size where it turns parallel.
#include "parallel_scan.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <numeric>
#include <random>
#include <vector>

namespace gridrt {
namespace {

TEST(ParallelScan, EqualsTheSerialPrefixSumAtEverySliceCount) {
  std::mt19937 random(7);
  for (int threads : {1, 2, 3, 7}) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
    for (size_t n : {size_t(0), size_t(1), size_t(1000), size_t(1) << 14, (size_t(1) << 14) + 3,
                     size_t(100003)}) {
      std::vector<int> values(n);
      for (int& v : values) v = int(random() % 50);
      std::vector<int> want(n);
      std::partial_sum(values.begin(), values.end(), want.begin());
      inclusiveScan(values.data(), n);
      EXPECT_EQ(values, want) << n << " values on " << threads << " threads";
    }
  }
}

}  // namespace
}  // namespace gridrt
