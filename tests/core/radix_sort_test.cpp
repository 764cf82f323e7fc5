#include "radix_sort.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

namespace gridrt {
namespace {

// Keys drawn from few values (many ties) and over many magnitudes, with the ints in
// increasing input order: the stable radix sort must give std::sort's order of the pairs.
TEST(RadixSort, OrdersPairsAsStdSortWhenTheIntsIncrease) {
  std::mt19937 random(7);
  for (int trial = 0; trial < 50; ++trial) {
    const int n = int(random() % 5000) + (trial == 0 ? 0 : 1);
    std::vector<std::pair<float, int>> items(n), scratch;
    std::uniform_int_distribution<int> tie(0, 9);
    std::uniform_real_distribution<float> exponent(-40.0f, 40.0f);
    for (int k = 0; k < n; ++k) {
      const float key = trial % 2 ? float(tie(random)) * 0.25f - 1.0f
                                  : std::exp2(exponent(random)) * (random() % 3 ? 1.0f : -1.0f);
      items[k] = {key, k};
    }
    std::vector<std::pair<float, int>> want = items;
    std::sort(want.begin(), want.end());
    radixSortByKey(items, scratch);
    ASSERT_EQ(items, want) << "trial " << trial << ", " << n << " pairs";
  }
}

// Keys whose 11-bit digits agree but for the last one (the passes that would only copy
// are skipped) and keys that are all equal.
TEST(RadixSort, SortsKeysDifferingInOneDigitAndEqualKeys) {
  std::vector<std::pair<float, int>> items, scratch;
  for (int k = 0; k < 100; ++k) items.push_back({1.0f + float((k * 37) % 100) * 0x1p-23f, k});
  std::vector<std::pair<float, int>> want = items;
  std::sort(want.begin(), want.end());
  radixSortByKey(items, scratch);
  EXPECT_EQ(items, want);
  std::vector<std::pair<float, int>> same(64, {3.5f, 0});
  for (int k = 0; k < 64; ++k) same[k].second = 63 - k;
  const auto before = same;
  radixSortByKey(same, scratch);
  EXPECT_EQ(same, before);  // stable: equal keys keep their order
}

TEST(RadixSort, OrderedFloatBitsFollowTheFloats) {
  const float ordered[] = {-INFINITY, -1e30f, -1.0f, -1e-40f, -0.0f,
                           0.0f,      1e-40f, 1.0f,  1e30f,   INFINITY};
  for (size_t k = 0; k + 1 < std::size(ordered); ++k)
    EXPECT_LT(orderedFloatBits(ordered[k]), orderedFloatBits(ordered[k + 1])) << k;
}

}  // namespace
}  // namespace gridrt
