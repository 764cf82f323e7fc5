// MappedFile: a file's bytes, mapped or read, equal what was written; an empty file and a
// FIFO (which cannot be mapped) are read; a missing file is an error in strerror's words.
#include "mapped_file.h"

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>

namespace gridrt {
namespace {

namespace fs = std::filesystem;

fs::path tempPath(const std::string& name) {
  return fs::temp_directory_path() /
         ("gridrt_mapped_file_" + std::to_string(getpid()) + "_" + name);
}

std::string patternOf(size_t size) {
  std::string text(size, '\0');
  for (size_t k = 0; k < size; ++k) text[k] = char((k * 131 + k / 7) & 0xff);
  return text;
}

bool equalBytes(const MappedFile& file, const std::string& text) {
  return file.size() == text.size() &&
         std::equal(text.begin(), text.end(), file.data(),
                    [](char a, unsigned char b) { return (unsigned char)(a) == b; });
}

TEST(MappedFile, HoldsEveryByteOfARegularFile) {
  for (size_t size : {size_t(1), size_t(4095), size_t(4096), size_t(3 << 20) + 7}) {
    const fs::path path = tempPath("regular");
    const std::string text = patternOf(size);
    std::ofstream(path, std::ios::binary).write(text.data(), std::streamsize(text.size()));
    MappedFile file;
    std::string error;
    ASSERT_TRUE(file.open(path.string(), error)) << error;
#if defined(__linux__)
    EXPECT_TRUE(file.mapped());
#endif
    EXPECT_TRUE(equalBytes(file, text)) << size;
    fs::remove(path);
  }
}

TEST(MappedFile, ReadsAnEmptyFile) {
  const fs::path path = tempPath("empty");
  std::ofstream(path, std::ios::binary).close();
  MappedFile file;
  std::string error;
  ASSERT_TRUE(file.open(path.string(), error)) << error;
  EXPECT_EQ(file.size(), 0u);
  fs::remove(path);
}

TEST(MappedFile, ReadsAFifoItCannotMap) {
  const fs::path path = tempPath("fifo");
  ASSERT_EQ(mkfifo(path.c_str(), 0600), 0);
  const std::string text = patternOf(100000);
  std::thread writer([&] {
    std::ofstream(path, std::ios::binary).write(text.data(), std::streamsize(text.size()));
  });
  MappedFile file;
  std::string error;
  const bool opened = file.open(path.string(), error);
  writer.join();
  ASSERT_TRUE(opened) << error;
  EXPECT_FALSE(file.mapped());
  EXPECT_TRUE(equalBytes(file, text));
  fs::remove(path);
}

TEST(MappedFile, AMissingFileIsAnError) {
  MappedFile file;
  std::string error;
  EXPECT_FALSE(file.open(tempPath("missing").string(), error));
  EXPECT_EQ(error, std::strerror(ENOENT));
}

TEST(MappedFile, OpeningAgainReleasesWhatItHeld) {
  const fs::path a = tempPath("a"), b = tempPath("b");
  std::ofstream(a, std::ios::binary) << "first file";
  std::ofstream(b, std::ios::binary) << "second";
  MappedFile file;
  std::string error;
  ASSERT_TRUE(file.open(a.string(), error));
  ASSERT_TRUE(file.open(b.string(), error));
  EXPECT_TRUE(equalBytes(file, "second"));
  fs::remove(a);
  fs::remove(b);
}

}  // namespace
}  // namespace gridrt
