#include "prefault.h"

#include <gtest/gtest.h>

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

}  // namespace
}  // namespace gridrt
