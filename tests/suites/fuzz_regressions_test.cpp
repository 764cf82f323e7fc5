// Replays the fuzzers' inputs in the ordinary test suite (no clang or libFuzzer needed):
// every seed and every frozen finding under tests/fuzz/ must load or be refused with
// SceneError (scenes), or parse or be refused with UsageError (command lines) — never
// crash or throw anything else. Built with GRIDRT_SANITIZE=ON, this also runs them under
// AddressSanitizer and UndefinedBehaviorSanitizer.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "errors.h"
#include "gltf_loader.h"
#include "options.h"
#include "test_support.h"

namespace {

namespace fs = std::filesystem;
using gridrt::test::sourcePath;

std::vector<fs::path> filesIn(const std::vector<std::string>& folders) {
  std::vector<fs::path> files;
  for (const auto& folder : folders) {
    std::error_code ec;
    for (const auto& entry : fs::directory_iterator(sourcePath(folder), ec))
      if (entry.is_regular_file() && entry.path().filename() != "README.md")
        files.push_back(entry.path());
  }
  return files;
}

std::string readBytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

// Split as tests/fuzz/fuzz_options.cpp does: on NUL and ASCII whitespace.
std::vector<std::string> words(const std::string& bytes) {
  std::vector<std::string> out{"gridrt"};
  std::string word;
  for (char c : bytes) {
    if (c == '\0' || c == ' ' || c == '\t' || c == '\n' || c == '\r') {
      if (!word.empty()) out.push_back(word);
      word.clear();
    } else {
      word.push_back(c);
    }
  }
  if (!word.empty()) out.push_back(word);
  return out;
}

TEST(FuzzRegressions, SceneInputsLoadOrFailWithSceneError) {
  auto files = filesIn({"tests/fuzz/corpus_scene", "tests/fuzz/regressions/scene"});
  ASSERT_FALSE(files.empty()) << "no inputs under tests/fuzz";
  for (const auto& file : files) {
    std::string bytes = readBytes(file);
    try {
      gridrt::loadGltfFromMemory(reinterpret_cast<const unsigned char*>(bytes.data()),
                                 bytes.size(), "", file.filename().string());
    } catch (const gridrt::SceneError&) {
      // refused cleanly
    } catch (const std::exception& e) {
      ADD_FAILURE() << file << ": unexpected exception: " << e.what();
    }
  }
}

TEST(FuzzRegressions, CommandLinesParseOrFailWithUsageError) {
  auto files = filesIn({"tests/fuzz/corpus_options", "tests/fuzz/regressions/options"});
  ASSERT_FALSE(files.empty()) << "no inputs under tests/fuzz";
  for (const auto& file : files) {
    std::vector<std::string> argv_words = words(readBytes(file));
    std::vector<const char*> argv;
    for (const auto& w : argv_words) argv.push_back(w.c_str());
    testing::internal::CaptureStdout();  // --help and --version print
    try {
      gridrt::parseCommandLine(int(argv.size()), argv.data());
    } catch (const gridrt::UsageError&) {
      // refused cleanly
    } catch (const std::exception& e) {
      ADD_FAILURE() << file << ": unexpected exception: " << e.what();
    }
    testing::internal::GetCapturedStdout();
  }
}

}  // namespace
