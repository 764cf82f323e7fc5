// readStreamBytes: every byte of a stream, whatever its size against the 1 MiB blocks, from
// where it stands, seekable or not.
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

TEST(FileBytes, ReadsTheRestOfAStreamAlreadyPartlyRead) {
  std::istringstream in("header:the rest of it");
  std::string header(7, '\0');
  in.read(header.data(), 7);
  std::vector<unsigned char> bytes;
  ASSERT_TRUE(readStreamBytes(in, bytes));
  EXPECT_EQ(std::string(bytes.begin(), bytes.end()), "the rest of it");
}

// A stream that can only be read forward, as a pipe: tellg fails, the blocks take over.
class ForwardOnlyBuffer : public std::streambuf {
 public:
  explicit ForwardOnlyBuffer(std::string text) : text_(std::move(text)) {
    setg(text_.data(), text_.data(), text_.data() + text_.size());
  }

 private:
  std::string text_;
};

TEST(FileBytes, ReadsAStreamThatCannotSeek) {
  const std::string text(3 * (size_t(1) << 20) + 11, 'x');
  ForwardOnlyBuffer buffer(text);
  std::istream in(&buffer);
  ASSERT_EQ(in.tellg(), std::streampos(-1));
  std::vector<unsigned char> bytes;
  ASSERT_TRUE(readStreamBytes(in, bytes));
  EXPECT_EQ(bytes.size(), text.size());
}

TEST(FileBytes, AReadErrorIsReported) {
  std::istringstream in("abc");
  in.setstate(std::ios::badbit);
  std::vector<unsigned char> bytes;
  EXPECT_FALSE(readStreamBytes(in, bytes));
}

}  // namespace
}  // namespace gridrt
