// --aov-file FILE.exr: the image (R, G, B, and A with --alpha) and AOVs as the layers of one
// OpenEXR file, ids as 32-bit unsigned integers: every AOV but the diagnostics, or the ones
// bare --aov NAME options name; the same values as the AOVs' own files, the miss values
// outside a crop window, frame patterns with --frames, and usage errors for the rest.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "image_output.h"
#include "run_command.h"
#include "test_support.h"

namespace gridrt {
namespace {

namespace fs = std::filesystem;
using test::CommandResult;
using test::joinArgs;
using test::runCommand;

constexpr int kWidth = 48, kHeight = 36;

bool haveDevice() { return test::gridrtHasDevice(); }

// The bunny (misses around it) at 48x36 with `args`.
std::vector<std::string> gridrt(const std::vector<std::string>& args) {
  return test::gridrtCommand(test::modelScene("bunny_res4.glb"), kWidth, kHeight, args);
}

void expectSuccess(const std::vector<std::string>& argv) {
  const CommandResult r = runCommand(argv);
  ASSERT_EQ(r.exit_code, 0) << joinArgs(argv) << "\n" << r.err;
}

std::vector<std::string> namesOf(const LayeredImage& image) {
  std::vector<std::string> names;
  for (const ImageChannel& c : image.channels) names.push_back(c.name);
  std::sort(names.begin(), names.end());
  return names;
}

const ImageChannel& channel(const LayeredImage& image, const std::string& name) {
  static const ImageChannel none;
  const int c = channelIndex(image, name);
  EXPECT_GE(c, 0) << "no channel " << name;
  return c >= 0 ? image.channels[c] : none;
}

// Channel `c` of an image read as interleaved floats.
std::vector<float> plane(const ImageData& image, int c) {
  std::vector<float> out;
  for (size_t p = 0; p < image.pixels.size() / image.channels; ++p)
    out.push_back(image.pixels[p * image.channels + c]);
  return out;
}

TEST(AovFile, HoldsTheImageAndEveryAovButTheDiagnosticsAsTheirOwnFilesDo) {
  if (!haveDevice()) GTEST_SKIP() << "no OpenCL device";
  const std::string dir = test::freshDir("aov_file_all");
  expectSuccess(
      gridrt({"-o", dir + "/image.exr", "--aov-file", dir + "/layers.exr", "--aov",
              "primid=" + dir + "/primid.exr", "--aov", "depth=" + dir + "/depth.exr", "--aov",
              "normal=" + dir + "/normal.exr", "--aov", "albedo=" + dir + "/albedo.exr"}));
  const LayeredImage layers = readLayeredImage(dir + "/layers.exr");
  EXPECT_EQ(namesOf(layers),
            (std::vector<std::string>{"B", "G", "R", "albedo.B", "albedo.G", "albedo.R", "depth.Z",
                                      "geonormal.X", "geonormal.Y", "geonormal.Z", "normal.X",
                                      "normal.Y", "normal.Z", "primid.id"}));
  for (const ImageChannel& c : layers.channels)
    EXPECT_EQ(c.type, c.name == "primid.id" ? SampleType::UInt : SampleType::Float) << c.name;
  // The image, and each AOV as its own file holds it.
  const ImageData image = readImage(dir + "/image.exr");
  for (int c = 0; c < 3; ++c)
    EXPECT_EQ(channel(layers, std::string(1, "RGB"[c])).floats, plane(image, c));
  const std::vector<uint32_t>& ids = channel(layers, "primid.id").uints;
  const std::vector<float> primid = plane(readImage(dir + "/primid.exr"), 0);
  ASSERT_EQ(ids.size(), primid.size());
  size_t misses = 0;
  for (size_t p = 0; p < ids.size(); ++p) {
    ASSERT_EQ(primid[p], float(int32_t(ids[p]))) << "pixel " << p;
    misses += ids[p] == 0xFFFFFFFFu;
  }
  EXPECT_GT(misses, 0u);
  EXPECT_LT(misses, ids.size());
  EXPECT_EQ(channel(layers, "depth.Z").floats, plane(readImage(dir + "/depth.exr"), 0));
  const ImageData normal = readImage(dir + "/normal.exr"), albedo = readImage(dir + "/albedo.exr");
  for (int c = 0; c < 3; ++c) {
    EXPECT_EQ(channel(layers, "normal." + std::string(1, "XYZ"[c])).floats, plane(normal, c));
    EXPECT_EQ(channel(layers, "albedo." + std::string(1, "RGB"[c])).floats, plane(albedo, c));
  }
}

// The tests AOV depends on the rays and the structure alone (ray_tests.h), not on which
// pairs the camera interrupt skipped on the device's threads: two runs, the same bits.
TEST(AovFile, TheTestsAovIsTheSameFromRunToRun) {
  if (!haveDevice()) GTEST_SKIP() << "no OpenCL device";
  const std::string dir = test::freshDir("aov_file_tests");
  std::vector<std::vector<float>> runs;
  for (const char* name : {"a", "b"}) {
    const std::string file = dir + "/tests_" + name + ".exr";
    expectSuccess(test::gridrtCommand(test::modelScene("bunny_res4.glb"), 320, 240,
                                      {"-o", dir + "/image.png", "--force", "--primary-only", "--aov",
                                       "tests=" + file}));
    runs.push_back(plane(readImage(file), 0));
  }
  EXPECT_EQ(runs[0], runs[1]);
  EXPECT_GT(*std::max_element(runs[0].begin(), runs[0].end()), 0.0f);
}

TEST(AovFile, BareAovsChooseTheLayersAndAlphaJoinsTheImage) {
  if (!haveDevice()) GTEST_SKIP() << "no OpenCL device";
  const std::string dir = test::freshDir("aov_file_bare");
  expectSuccess(gridrt({"-o", dir + "/image.png", "--aov-file", dir + "/layers.exr", "--aov", "pe",
                        "--aov", "depth", "--alpha"}));
  const LayeredImage layers = readLayeredImage(dir + "/layers.exr");
  EXPECT_EQ(namesOf(layers), (std::vector<std::string>{"A", "B", "G", "R", "depth.Z", "pe.id"}));
  EXPECT_EQ(channel(layers, "pe.id").type, SampleType::UInt);
}

TEST(AovFile, OutsideACropWindowTheLayersHoldTheirMissValues) {
  if (!haveDevice()) GTEST_SKIP() << "no OpenCL device";
  const std::string dir = test::freshDir("aov_file_crop");
  expectSuccess(gridrt({"-o", dir + "/full.exr", "--aov-file", dir + "/full_layers.exr"}));
  expectSuccess(gridrt(
      {"-o", dir + "/crop.exr", "--aov-file", dir + "/crop_layers.exr", "--crop", "10,6,37,29"}));
  const LayeredImage full = readLayeredImage(dir + "/full_layers.exr"),
                     crop = readLayeredImage(dir + "/crop_layers.exr");
  ASSERT_EQ(namesOf(full), namesOf(crop));
  for (const ImageChannel& c : crop.channels) {
    const ImageChannel& whole = channel(full, c.name);
    const bool miss_is_minus_one = c.name == "depth.Z" || c.name == "primid.id";
    for (int y = 0; y < kHeight; ++y)
      for (int x = 0; x < kWidth; ++x) {
        const size_t p = size_t(y) * kWidth + x;
        const bool inside = x >= 10 && x < 37 && y >= 6 && y < 29;
        if (c.type == SampleType::UInt) {
          ASSERT_EQ(c.uints[p], inside ? whole.uints[p] : 0xFFFFFFFFu) << c.name << " " << p;
        } else {
          ASSERT_EQ(c.floats[p], inside              ? whole.floats[p]
                                 : miss_is_minus_one ? -1.0f
                                                     : 0.0f)
              << c.name << " " << p;
        }
      }
  }
}

TEST(AovFile, FramesWriteOneFilePerFrame) {
  if (!haveDevice()) GTEST_SKIP() << "no OpenCL device";
  const std::string dir = test::freshDir("aov_file_frames");
  expectSuccess(gridrt({"--frames", "0:1", "-o", dir + "/image_%d.png", "--aov-file",
                        dir + "/layers_%d.exr", "--aov", "primid"}));
  EXPECT_EQ(test::listDir(dir), (std::vector<std::string>{"image_0.png", "image_1.png",
                                                          "layers_0.exr", "layers_1.exr"}));
  const CommandResult r = runCommand(
      gridrt({"--frames", "0:1", "-o", dir + "/i_%d.png", "--aov-file", dir + "/l.exr"}));
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("--aov-file"), std::string::npos) << r.err;
}

TEST(AovFile, MisusesAreUsageErrorsAndWriteNothing) {
  const std::string dir = test::freshDir("aov_file_usage");
  const std::string image = dir + "/image.exr", layers = dir + "/layers.exr";
  struct Case {
    std::vector<std::string> args;
    std::string message;
  };
  const std::vector<Case> cases{
      {{"-o", image, "--aov", "depth"}, "--aov depth: without =FILE only with --aov-file"},
      {{"-o", image, "--aov-file", dir + "/layers.tif"},
       "--aov-file: '" + dir + "/layers.tif' is not an .exr file"},
      {{"-o", image, "--aov-file", "-"}, "--aov-file: only -o can write to standard output"},
      {{"-o", image, "--aov-file", image},
       "--aov-file: writes '" + image + "', the file -o writes"},
      {{"-o", image, "--aov", "depth=" + layers, "--aov-file", layers},
       "--aov-file: writes '" + layers + "', the file --aov depth writes"},
      {{"-o", image, "--aov-file", layers, "--aov", "pe", "--accel", "brute"},
       "--aov pe: only the grid intersectors"},
      {{"-o", image, "--aov-file", layers, "--aov", "color"}, "--aov: expected NAME=FILE or NAME"},
  };
  for (const Case& c : cases) {
    const CommandResult r = runCommand(gridrt(c.args));
    EXPECT_EQ(r.exit_code, 2) << joinArgs(c.args) << "\n" << r.err;
    EXPECT_EQ(r.err.rfind("gridrt: " + c.message, 0), 0u) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  }
  EXPECT_TRUE(test::listDir(dir).empty());
}

}  // namespace
}  // namespace gridrt
