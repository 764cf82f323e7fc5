#include "prefault.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

namespace gridrt {
namespace {

// Prefaulting backs pages and leaves what they hold: a buffer filled first keeps every
// byte, whatever the range's alignment, and a reserved capacity can be filled afterwards.
TEST(Prefault, LeavesTheContentsAsTheyAre) {
  std::vector<unsigned char> bytes(size_t(9) << 20);
  for (size_t k = 0; k < bytes.size(); ++k) bytes[k] = static_cast<unsigned char>(k * 131 + 7);
  prefaultForWriting(bytes.data() + 1001, bytes.size() - 3003);
  prefaultForWriting(bytes.data(), 100);  // below kPrefaultMinBytes: nothing
  for (size_t k = 0; k < bytes.size(); ++k)
    ASSERT_EQ(bytes[k], static_cast<unsigned char>(k * 131 + 7)) << k;

  std::vector<int> reserved(10, 3);
  reserveFaultedIn(reserved, size_t(4) << 20);
  EXPECT_GE(reserved.capacity(), size_t(4) << 20);
  reserved.resize(reserved.capacity(), 5);
  for (int v : reserved) ASSERT_EQ(v, 5);
}

// resizeFaultedIn is resize: the elements kept, the new ones value-initialised, whether it
// grows past the capacity (a fresh buffer), within it, or shrinks.
TEST(Prefault, ResizeFaultedInIsResize) {
  struct Pair {
    int a;
    float b;
  };
  std::vector<Pair> v;
  for (size_t n : {size_t(3), size_t(1) << 20, (size_t(1) << 20) + 5, size_t(7), size_t(3) << 20}) {
    const size_t before = v.size();
    for (size_t k = 0; k < before; ++k) v[k] = {int(k), float(k) * 0.5f};
    resizeFaultedIn(v, n);
    ASSERT_EQ(v.size(), n);
    for (size_t k = 0; k < std::min(before, n); ++k) {
      ASSERT_EQ(v[k].a, int(k)) << k;
      ASSERT_EQ(v[k].b, float(k) * 0.5f) << k;
    }
    for (size_t k = before; k < n; ++k) {
      ASSERT_EQ(v[k].a, 0) << k;
      ASSERT_EQ(v[k].b, 0.0f) << k;
    }
  }
}

}  // namespace
}  // namespace gridrt
