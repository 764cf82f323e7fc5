// Replays the fuzzers' inputs in the ordinary test suite (no clang or libFuzzer needed):
// every seed under tests/fuzz/corpus_* is a valid input (it loads, or parses), every frozen
// scene finding is refused with SceneError and every frozen command line parses or is
// refused with UsageError — never a crash or anything else thrown. Each folder must exist
// and hold inputs. Built with GRIDRT_SANITIZE=ON, this also runs them under
// AddressSanitizer and UndefinedBehaviorSanitizer.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "animated_scene.h"
#include "errors.h"
#include "gltf_loader.h"
#include "options.h"
#include "test_support.h"

namespace {

namespace fs = std::filesystem;
using gridrt::test::sourcePath;

// The files of one folder under tests/fuzz (its README aside); a missing or empty folder
// fails the test (a moved corpus must not pass by replaying nothing).
std::vector<fs::path> filesIn(const std::string& folder) {
  std::vector<fs::path> files;
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(sourcePath(folder), ec))
    if (entry.is_regular_file() && entry.path().filename() != "README.md")
      files.push_back(entry.path());
  EXPECT_FALSE(ec) << sourcePath(folder) << ": " << ec.message();
  EXPECT_FALSE(files.empty()) << "no inputs in " << sourcePath(folder);
  std::sort(files.begin(), files.end());
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

enum class Outcome { Accepted, Refused, Other };
std::ostream& operator<<(std::ostream& out, Outcome o) {
  return out << (o == Outcome::Accepted ? "accepted" : o == Outcome::Refused ? "refused" : "other");
}

Outcome loadScene(const fs::path& file, std::string& what) {
  std::string bytes = readBytes(file);
  try {
    // As tests/fuzz/fuzz_scene_loader.cpp does: the still pose, then the animations posed.
    const gridrt::GltfDocument document =
        gridrt::GltfDocument::fromMemory(reinterpret_cast<const unsigned char*>(bytes.data()),
                                         bytes.size(), "", file.filename().string());
    document.flatten();
    if (!document.model().animations.empty()) {
      const gridrt::AnimatedScene animated(document, {}, "");
      for (double t : {-1.0, 0.0, 0.37, 1e9}) animated.at(t);
    }
    return Outcome::Accepted;
  } catch (const gridrt::SceneError& e) {
    what = e.what();
    return Outcome::Refused;
  } catch (const std::exception& e) {
    what = e.what();
    return Outcome::Other;
  }
}

Outcome parseWords(const fs::path& file, std::string& what) {
  std::vector<std::string> argv_words = words(readBytes(file));
  std::vector<const char*> argv;
  for (const auto& w : argv_words) argv.push_back(w.c_str());
  testing::internal::CaptureStdout();  // --help and --version print
  Outcome outcome = Outcome::Accepted;
  try {
    gridrt::parseCommandLine(int(argv.size()), argv.data());
  } catch (const gridrt::UsageError& e) {
    what = e.what();
    outcome = Outcome::Refused;
  } catch (const std::exception& e) {
    what = e.what();
    outcome = Outcome::Other;
  }
  testing::internal::GetCapturedStdout();
  return outcome;
}

// The seeds are valid inputs: each loads, so the fuzzer starts from inputs that go deep.
TEST(FuzzRegressions, EverySceneSeedLoads) {
  for (const auto& file : filesIn("tests/fuzz/corpus_scene")) {
    std::string what;
    EXPECT_EQ(loadScene(file, what), Outcome::Accepted) << file << ": " << what;
  }
}

// The frozen findings are bad inputs: each is refused with SceneError, nothing else.
TEST(FuzzRegressions, EverySceneFindingIsRefusedWithSceneError) {
  for (const auto& file : filesIn("tests/fuzz/regressions/scene")) {
    std::string what;
    EXPECT_EQ(loadScene(file, what), Outcome::Refused) << file << ": " << what;
  }
}

TEST(FuzzRegressions, EveryCommandLineSeedParses) {
  for (const auto& file : filesIn("tests/fuzz/corpus_options")) {
    std::string what;
    EXPECT_EQ(parseWords(file, what), Outcome::Accepted) << file << ": " << what;
  }
}

// The frozen command lines parse or are refused with UsageError (some, like a device
// index past every table, are refused only when the device is looked up), never anything
// else.
TEST(FuzzRegressions, EveryCommandLineFindingParsesOrIsRefusedWithUsageError) {
  for (const auto& file : filesIn("tests/fuzz/regressions/options")) {
    std::string what;
    EXPECT_NE(parseWords(file, what), Outcome::Other) << file << ": " << what;
  }
}

}  // namespace
