// Program binaries kept between runs (program_binary_cache.h): a second runtime loads what
// the first compiled and computes the same hits; an entry that does not match its key, a
// truncated or damaged one is a miss that is compiled again and replaced (a damaged
// binary handed to PoCL 3.1 crashes it); a cache that cannot be written is no error.
#include "program_binary_cache.h"

#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "brute_intersector.h"
#include "cl_runtime.h"
#include "default_scene.h"
#include "prepared_triangles.h"
#include "test_support.h"

namespace fs = std::filesystem;

namespace gridrt {
namespace {

std::string fileBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

void writeBytes(const std::string& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes;
}

// ctest gives every test (and the gridrt it runs) the build's own cache folder (run
// outside ctest, this test fails: GRIDRT_CACHE_DIR is not set there).
TEST(ProgramBinaryCache, TestsRunThroughCtestUseTheBuildsOwnCacheFolder) {
  EXPECT_EQ(ProgramBinaryCache::defaultDir(), GRIDRT_TEST_CACHE_DIR)
      << "run through ctest, which sets GRIDRT_CACHE_DIR to the build's test-cache folder";
}

TEST(ProgramBinaryCache, AnEntryComesBackOnlyForItsOwnKey) {
  const ProgramBinaryCache cache(test::freshDir("binary_cache_keys"));
  const std::vector<unsigned char> binary{1, 2, 3, 0, 255};
  EXPECT_FALSE(cache.load("key a"));
  cache.store("key a", binary);
  ASSERT_TRUE(cache.load("key a"));
  EXPECT_EQ(*cache.load("key a"), binary);
  EXPECT_FALSE(cache.load("key b"));
  // Another key's entry under this key's name (as a hash collision would put it): a miss.
  writeBytes(cache.pathOf("key b"), fileBytes(cache.pathOf("key a")));
  EXPECT_FALSE(cache.load("key b"));
  // A truncated entry (the binary cut short, only the header, the header cut short) or
  // one byte of the binary changed: a miss.
  const std::string whole = fileBytes(cache.pathOf("key a"));
  for (size_t cut : {size_t(1), binary.size(), whole.size() - 10}) {
    writeBytes(cache.pathOf("key a"), whole.substr(0, whole.size() - cut));
    EXPECT_FALSE(cache.load("key a")) << "cut " << cut;
  }
  std::string changed = whole;
  changed[changed.size() - 2] ^= 1;
  writeBytes(cache.pathOf("key a"), changed);
  EXPECT_FALSE(cache.load("key a"));
  writeBytes(cache.pathOf("key a"), whole);
  EXPECT_TRUE(cache.load("key a"));
  // No temporary files are left behind.
  EXPECT_EQ(test::listDir(cache.dir()).size(), 2u);
}

TEST(ProgramBinaryCache, KeepsTheEntriesUsedLast) {
  const ProgramBinaryCache cache(test::freshDir("binary_cache_prune"));
  const size_t limit = ProgramBinaryCache::kMaxEntries;
  // Entries stored a second apart (file times set, so the order does not hang on the
  // file system's clock resolution); entry 0 is loaded, i.e. used, after all the others.
  const auto start = fs::file_time_type::clock::now() - std::chrono::hours(1);
  auto key = [](size_t k) { return "key " + std::to_string(k); };
  for (size_t k = 0; k < limit; ++k) {
    cache.store(key(k), {1, 2, 3});
    fs::last_write_time(cache.pathOf(key(k)), start + std::chrono::seconds(k));
  }
  EXPECT_EQ(test::listDir(cache.dir()).size(), limit);
  ASSERT_TRUE(cache.load(key(0)));
  for (size_t k = limit; k < limit + 5; ++k) {
    cache.store(key(k), {1, 2, 3});
    fs::last_write_time(cache.pathOf(key(k)), start + std::chrono::seconds(k));
  }
  EXPECT_EQ(test::listDir(cache.dir()).size(), limit);
  EXPECT_TRUE(cache.load(key(0)));  // used last of the first ones
  for (size_t k = 1; k <= 5; ++k) EXPECT_FALSE(cache.load(key(k))) << k;  // the oldest went
  for (size_t k = 6; k < limit + 5; ++k) EXPECT_TRUE(cache.load(key(k))) << k;
}

TEST(ProgramBinaryCache, AStoreRemovesTemporaryFilesLeftAnHourAgo) {
  const ProgramBinaryCache cache(test::freshDir("binary_cache_temps"));
  const std::string old_temp = cache.pathOf("gone") + ".tmp12345";
  const std::string new_temp = cache.pathOf("writing") + ".tmp23456";  // being written now
  writeBytes(old_temp, "half");
  writeBytes(new_temp, "half");
  fs::last_write_time(old_temp, fs::file_time_type::clock::now() - std::chrono::hours(2));
  cache.store("key", {1, 2, 3});
  EXPECT_FALSE(fs::exists(old_temp));
  EXPECT_TRUE(fs::exists(new_temp));
  EXPECT_TRUE(cache.load("key"));
}

TEST(ProgramBinaryCache, NoDirectoryOrAnUnwritableOneIsNoError) {
  const ProgramBinaryCache none("");
  none.store("key", {1, 2, 3});
  EXPECT_FALSE(none.load("key"));
  // A directory below a regular file can never be made.
  const std::string file = test::tempPath("binary_cache_file");
  writeBytes(file, "x");
  const ProgramBinaryCache blocked(file + "/cache");
  blocked.store("key", {1, 2, 3});
  EXPECT_FALSE(blocked.load("key"));
}

class ProgramBinaries : public ::testing::Test {
 protected:
  void SetUp() override {
    if (listDevices().empty()) GTEST_SKIP() << "no OpenCL device: install pocl-opencl-icd";
    scene_ = makeDefaultScene();
    triangles_ = prepareTriangles(scene_);
    rays_.clear();
    for (int i = 0; i < 256; ++i) {  // a fan from the camera's eye across the box
      const float a = -0.6f + 1.2f * float(i % 16) / 15.0f, b = 0.1f + 0.8f * float(i / 16) / 15.0f;
      rays_.push_back(GrRay{0.0f, 0.5f, 1.0f, 0.0f, a, b - 0.5f, -1.0f, 1e30f});
    }
  }
  // The brute-force hits of rays_ through a runtime on `dir`, and its program counts.
  std::vector<GrHit> trace(const std::string& dir, int& loaded, int& compiled) {
    ClRuntime runtime("", dir);
    BruteIntersector brute(runtime, triangles_);
    std::vector<GrHit> hits;
    brute.intersect(rays_, HitMode::Closest, hits, nullptr);
    loaded = runtime.programsLoaded();
    compiled = runtime.programsCompiled();
    return hits;
  }
  Scene scene_;
  std::vector<GrTriangle> triangles_;
  std::vector<GrRay> rays_;
};

TEST_F(ProgramBinaries, ASecondRuntimeLoadsWhatTheFirstCompiled) {
  const std::string dir = test::freshDir("binary_cache_runtime");
  int loaded = 0, compiled = 0;
  const std::vector<GrHit> first = trace(dir, loaded, compiled);
  EXPECT_EQ(loaded, 0);
  EXPECT_EQ(compiled, 1);
  ASSERT_EQ(test::listDir(dir).size(), 1u);
  const std::vector<GrHit> second = trace(dir, loaded, compiled);
  EXPECT_EQ(loaded, 1);
  EXPECT_EQ(compiled, 0);
  EXPECT_EQ(test::hitMismatches(first, second, "binary"), 0u);
  size_t hit = 0;
  for (const GrHit& h : first) hit += h.prim >= 0;
  EXPECT_GT(hit, rays_.size() / 2);  // the rays do hit the box
}

TEST_F(ProgramBinaries, ADamagedBinaryIsCompiledAgainAndReplaced) {
  const std::string dir = test::freshDir("binary_cache_refused");
  int loaded = 0, compiled = 0;
  const std::vector<GrHit> first = trace(dir, loaded, compiled);
  ASSERT_EQ(test::listDir(dir).size(), 1u);
  const std::string entry = dir + "/" + test::listDir(dir)[0];
  // The right key, then bytes that are no program binary (the driver never sees them).
  std::string bytes = fileBytes(entry);
  const size_t body = bytes.size() / 2;
  std::fill(bytes.begin() + bytes.size() - body, bytes.end(), 'x');
  writeBytes(entry, bytes);
  const std::vector<GrHit> second = trace(dir, loaded, compiled);
  EXPECT_EQ(loaded, 0);
  EXPECT_EQ(compiled, 1);
  EXPECT_EQ(test::hitMismatches(first, second, "binary"), 0u);
  trace(dir, loaded, compiled);  // the entry was replaced by a good one
  EXPECT_EQ(loaded, 1);
}

}  // namespace
}  // namespace gridrt
