#include "uninitialized_vector.h"

#include <gtest/gtest.h>

#include <cstddef>

namespace gridrt {
namespace {

// resize within the capacity leaves what the memory holds: bytes written before a shrink
// are there again after growing back (a std::vector would zero them). Read as unsigned char,
// whose indeterminate values may be read.
TEST(UninitializedVector, ResizeLeavesTheMemoryAsItIs) {
  constexpr size_t kBytes = 4096;
  UninitializedVector<unsigned char> bytes(kBytes, static_cast<unsigned char>(0xAB));
  for (unsigned char b : bytes) ASSERT_EQ(b, 0xAB);
  bytes.resize(1);
  bytes.resize(kBytes);
  ASSERT_EQ(bytes.capacity(), kBytes);
  for (size_t k = 0; k < kBytes; ++k) ASSERT_EQ(bytes[k], 0xAB) << k;
}

// Every other way of making elements is std::vector's: copies, values and initialiser lists.
TEST(UninitializedVector, ValuesAndCopiesAreConstructedAsGiven) {
  struct Pair {
    int a;
    float b;
  };
  UninitializedVector<Pair> v(3, Pair{4, 0.5f});
  v.push_back({7, 1.5f});
  v.resize(6, Pair{9, 2.5f});
  const UninitializedVector<Pair> copy = v;
  const int want_a[] = {4, 4, 4, 7, 9, 9};
  const float want_b[] = {0.5f, 0.5f, 0.5f, 1.5f, 2.5f, 2.5f};
  ASSERT_EQ(copy.size(), 6u);
  for (size_t k = 0; k < copy.size(); ++k) {
    EXPECT_EQ(copy[k].a, want_a[k]) << k;
    EXPECT_EQ(copy[k].b, want_b[k]) << k;
  }
}

}  // namespace
}  // namespace gridrt
