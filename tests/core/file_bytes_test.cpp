// readStreamBytes: every byte of a stream, whatever its size against the 1 MiB blocks.
#include "file_bytes.h"

#include <gtest/gtest.h>

#include <sstream>
#include <string>

namespace gridrt {
namespace {

TEST(FileBytes, ReadsEveryByteWhateverTheSizeAgainstTheBlocks) {
  const size_t mib = size_t(1) << 20;
  for (size_t size : {size_t(0), size_t(1), mib - 1, mib, mib + 1, 3 * mib + 5}) {
    std::string text(size, '\0');
    for (size_t k = 0; k < size; ++k) text[k] = char((k * 131 + k / 7) & 0xff);
    std::istringstream in(text);
    std::vector<unsigned char> bytes{1, 2, 3};  // replaced, not appended to
    ASSERT_TRUE(readStreamBytes(in, bytes)) << size;
    ASSERT_EQ(bytes.size(), size);
    EXPECT_TRUE(std::equal(bytes.begin(), bytes.end(), text.begin(), [](unsigned char a, char b) {
      return a == (unsigned char)(b);
    })) << size;
  }
}

TEST(FileBytes, AReadErrorIsReported) {
  std::istringstream in("abc");
  in.setstate(std::ios::badbit);
  std::vector<unsigned char> bytes;
  EXPECT_FALSE(readStreamBytes(in, bytes));
}

}  // namespace
}  // namespace gridrt
