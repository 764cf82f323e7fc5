// --alpha: the image gets an alpha channel A, each pixel's share of camera samples whose
// ray hit the scene (every --spp sample, adaptive refinement, crop windows), with the colour
// associated with it in .exr (the background's share taken out) and unassociated in .png;
// formats without alpha are refused.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <set>
#include <string>
#include <vector>

#include "image_output.h"
#include "run_command.h"
#include "test_support.h"

namespace gridrt {
namespace {

using test::CommandResult;
using test::joinArgs;
using test::runCommand;
using test::tempPath;

constexpr int kWidth = 48, kHeight = 36;
const std::vector<float> kBackground{0.2f, 0.4f, 0.6f};

bool haveDevice() { return test::gridrtHasDevice(); }

// The bunny (background around it) at 48x36 with `flags`.
std::vector<std::string> gridrt(const std::vector<std::string>& flags) {
  std::vector<std::string> argv = {"--background", "0.2,0.4,0.6"};
  argv.insert(argv.end(), flags.begin(), flags.end());
  return test::gridrtCommand(test::modelScene("bunny_res4.glb"), kWidth, kHeight, argv);
}

LayeredImage rendered(const std::string& name, const std::vector<std::string>& flags) {
  const std::string path = tempPath(name);
  std::vector<std::string> argv = gridrt(flags);
  argv.insert(argv.end(), {"-o", path});
  const CommandResult r = runCommand(argv);
  EXPECT_EQ(r.exit_code, 0) << joinArgs(argv) << "\n" << r.err;
  return r.exit_code == 0 ? readLayeredImage(path) : LayeredImage{};
}

const std::vector<float>& channel(const LayeredImage& image, const std::string& name) {
  static const std::vector<float> none;
  const int c = channelIndex(image, name);
  EXPECT_GE(c, 0) << "no channel " << name;
  return c >= 0 ? image.channels[c].floats : none;
}

// The distinct values of `values`.
std::set<float> distinct(const std::vector<float>& values) {
  return std::set<float>(values.begin(), values.end());
}

TEST(Alpha, IsTheShareOfCameraSamplesThatHitAndTheColourIsPremultiplied) {
  if (!haveDevice()) GTEST_SKIP() << "no OpenCL device";
  const LayeredImage plain = rendered("plain.exr", {"--spp", "4"});
  const LayeredImage with = rendered("alpha.exr", {"--spp", "4", "--alpha"});
  ASSERT_EQ(plain.channels.size(), 3u) << "no alpha without --alpha";
  ASSERT_EQ(with.channels.size(), 4u);
  const std::vector<float>& a = channel(with, "A");
  ASSERT_EQ(a.size(), size_t(kWidth) * kHeight);
  // Four samples a pixel: quarters, and all five of them somewhere around the bunny.
  EXPECT_EQ(distinct(a), (std::set<float>{0.0f, 0.25f, 0.5f, 0.75f, 1.0f}));
  for (int c = 0; c < 3; ++c) {
    const std::string name(1, "RGB"[c]);
    const std::vector<float>&want = channel(plain, name), &got = channel(with, name);
    for (size_t p = 0; p < a.size(); ++p) {
      if (a[p] == 1.0f)  // covered: the colour as rendered
        ASSERT_EQ(got[p], want[p]) << name << " at " << p;
      else if (a[p] == 0.0f)  // the background alone: nothing of it is left
        ASSERT_EQ(got[p], 0.0f) << name << " at " << p;
      else  // over the background it gives the rendered colour again
        ASSERT_NEAR(got[p] + (1.0f - a[p]) * kBackground[c], want[p], 1e-6f) << name << " at " << p;
    }
  }
}

TEST(Alpha, OneSampleAPixelCoversWhereTheCameraRayHit) {
  if (!haveDevice()) GTEST_SKIP() << "no OpenCL device";
  const std::string primid = tempPath("primid.exr");
  const LayeredImage image = rendered("centre.exr", {"--alpha", "--aov", "primid=" + primid});
  const std::vector<float>& a = channel(image, "A");
  const ImageData ids = readImage(primid);
  ASSERT_EQ(ids.pixels.size(), a.size());
  size_t covered = 0;
  for (size_t p = 0; p < a.size(); ++p) {
    ASSERT_EQ(a[p], ids.pixels[p] >= 0.0f ? 1.0f : 0.0f) << "pixel " << p;
    covered += a[p] == 1.0f;
  }
  EXPECT_GT(covered, 0u);
  EXPECT_LT(covered, a.size());
}

TEST(Alpha, AdaptiveRefinementCountsEverySample) {
  if (!haveDevice()) GTEST_SKIP() << "no OpenCL device";
  const LayeredImage image = rendered(
      "adaptive.exr", {"--alpha", "--aa", "adaptive", "--aa-samples", "3", "--aa-threshold", "0"});
  // The centre and three more where neighbours differ: quarters again, edges partly covered.
  const std::set<float> values = distinct(channel(image, "A"));
  for (float v : values) EXPECT_EQ(v * 4.0f, std::round(v * 4.0f)) << v;
  EXPECT_TRUE(values.count(0.0f) && values.count(1.0f));
  EXPECT_GT(values.size(), 2u) << "refined edge pixels are partly covered";
}

TEST(Alpha, ACropWindowHasTheFullRendersAlphaAndNoneOutside) {
  if (!haveDevice()) GTEST_SKIP() << "no OpenCL device";
  const LayeredImage whole = rendered("full.exr", {"--alpha", "--spp", "4"});
  const std::vector<float>& full = channel(whole, "A");
  const int x0 = 10, y0 = 6, x1 = 37, y1 = 29;
  const LayeredImage cropped =
      rendered("crop.exr", {"--alpha", "--spp", "4", "--crop", "10,6,37,29"});
  const LayeredImage window = rendered(
      "window.exr", {"--alpha", "--spp", "4", "--crop", "10,6,37,29", "--crop-output", "window"});
  const std::vector<float>&a = channel(cropped, "A"), &w = channel(window, "A");
  ASSERT_EQ(a.size(), full.size());
  ASSERT_EQ(w.size(), size_t(x1 - x0) * (y1 - y0));
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) {
      const size_t p = size_t(y) * kWidth + x;
      const bool inside = x >= x0 && x < x1 && y >= y0 && y < y1;
      ASSERT_EQ(a[p], inside ? full[p] : 0.0f) << x << "," << y;
      if (inside) {
        ASSERT_EQ(w[size_t(y - y0) * (x1 - x0) + (x - x0)], full[p]) << x << "," << y;
      }
    }
}

TEST(Alpha, APngHoldsItIn8BitsAndCoveredPixelsKeepTheirColour) {
  if (!haveDevice()) GTEST_SKIP() << "no OpenCL device";
  const LayeredImage exr = rendered("exact.exr", {"--alpha", "--spp", "4"});
  const std::vector<float>& exact = channel(exr, "A");
  const std::string plain = tempPath("plain.png"), with = tempPath("alpha.png");
  for (const auto& [path, alpha] : {std::pair{plain, false}, std::pair{with, true}}) {
    std::vector<std::string> argv = gridrt({"--spp", "4", "-o", path});
    if (alpha) argv.push_back("--alpha");
    const CommandResult r = runCommand(argv);
    ASSERT_EQ(r.exit_code, 0) << joinArgs(argv) << "\n" << r.err;
  }
  const ImageData want = readImage(plain), got = readImage(with);
  ASSERT_EQ(want.channels, 3);
  ASSERT_EQ(got.channels, 4);
  ASSERT_EQ(got.pixels.size() / 4, exact.size());
  for (size_t p = 0; p < exact.size(); ++p) {
    ASSERT_NEAR(got.pixels[4 * p + 3], std::round(exact[p] * 255.0f) / 255.0f, 1e-6f) << p;
    if (exact[p] != 1.0f) continue;
    for (int c = 0; c < 3; ++c) ASSERT_EQ(got.pixels[4 * p + c], want.pixels[3 * p + c]) << p;
  }
}

TEST(Alpha, AFormatWithoutAlphaIsAUsageError) {
  for (const std::vector<std::string>& output :
       {std::vector<std::string>{"-o", tempPath("a.jpg")},
        std::vector<std::string>{"-o", tempPath("a.hdr")},
        std::vector<std::string>{"-o", "-", "--format", "jpg"}}) {
    std::vector<std::string> argv = gridrt(output);
    argv.push_back("--alpha");
    const CommandResult r = runCommand(argv);
    EXPECT_EQ(r.exit_code, 2) << joinArgs(argv);
    EXPECT_NE(r.err.find("--alpha: "), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(output[1] == "-" ? "standard output is jpg" : output[1]),
              std::string::npos)
        << r.err;
    EXPECT_NE(r.err.find("has no alpha channel"), std::string::npos) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_TRUE(r.out.empty());
    if (output[1] != "-") {
      EXPECT_FALSE(std::filesystem::exists(output[1]));
    }
  }
}

}  // namespace
}  // namespace gridrt
