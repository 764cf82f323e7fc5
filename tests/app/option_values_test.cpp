// Every numeric option is checked the same way: a whole number where an integer is
// expected, a finite number in range elsewhere, one message for each kind of mistake; and
// a bad value on the command line is a usage error (exit 2) wherever it is found.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "errors.h"
#include "image_output.h"
#include "options.h"
#include "run_command.h"
#include "test_support.h"

namespace gridrt {
namespace {

// The UsageError parseCommandLine throws for `args`, or "<accepted>".
std::string usageError(std::vector<std::string> args) {
  args.insert(args.begin(), "gridrt");
  std::vector<const char*> argv;
  for (const auto& a : args) argv.push_back(a.c_str());
  try {
    parseCommandLine(int(argv.size()), argv.data());
  } catch (const UsageError& e) {
    return e.what();
  }
  return "<accepted>";
}

struct BadValue {
  std::vector<std::string> args;
  std::string message;
};

class OptionValues : public testing::TestWithParam<BadValue> {};

TEST_P(OptionValues, AreRefusedWithAMessageNamingTheMistake) {
  const std::string message = usageError(GetParam().args);
  EXPECT_NE(message.find(GetParam().message), std::string::npos) << message;
  EXPECT_EQ(message.find('\n'), std::string::npos) << message;
}

INSTANTIATE_TEST_SUITE_P(
    NotANumber, OptionValues,
    testing::Values(
        BadValue{{"--fov", "nan"}, "--fov: expected a finite number in 0.01..179, got 'nan'"},
        BadValue{{"--ambient", "nan"}, "--ambient: expected a finite number"},
        BadValue{{"--min-path-weight", "nan"}, "--min-path-weight: expected a finite number"},
        BadValue{{"--grid-density", "nan"}, "--grid-density: expected a finite number"},
        BadValue{{"--aa-threshold", "inf"}, "--aa-threshold: expected a finite number"},
        BadValue{{"--ambient", "abc"}, "--ambient: expected a number, got 'abc'"},
        BadValue{{"--fov", "30deg"}, "--fov: expected a number, got '30deg'"}));

INSTANTIATE_TEST_SUITE_P(
    NotAnInteger, OptionValues,
    testing::Values(BadValue{{"--spp", "1.5"}, "--spp: expected an integer, got '1.5'"},
                    BadValue{{"--width", "1e3"}, "--width: expected an integer, got '1e3'"},
                    BadValue{{"--height", ""}, "--height: expected an integer"},
                    BadValue{{"--repeat", "x"}, "--repeat: expected an integer"}));

INSTANTIATE_TEST_SUITE_P(
    OutOfRange, OptionValues,
    testing::Values(BadValue{{"--spp", "0"}, "--spp: expected an integer in 1..4096, got '0'"},
                    BadValue{{"--max-depth", "65"}, "--max-depth: expected an integer in 0..64"},
                    BadValue{{"--fov", "180"}, "--fov: expected a finite number in 0.01..179"},
                    BadValue{{"--min-path-weight", "1.5"},
                             "--min-path-weight: expected a finite number in 0..1"}));

// Options that mean nothing alone, and outputs that would overwrite each other: refused,
// never ignored in silence.
INSTANTIATE_TEST_SUITE_P(
    IgnoredOrOverwritten, OptionValues,
    testing::Values(
        BadValue{{"--aa-samples", "4"}, "--aa-samples: only with --aa adaptive"},
        BadValue{{"--aa-threshold", "0.2"}, "--aa-threshold: only with --aa adaptive"},
        BadValue{{"--grid", "8,8,8", "--grid-density", "0.5"}, "--grid-density: only with --grid"},
        BadValue{{"--crop-output", "window"}, "--crop-output: only with --crop"},
        BadValue{{"--accel", "brute", "--aov", "pe=pe.exr"}, "--aov pe: only the grid"},
        BadValue{{"--accel", "reference", "--aov", "listlen=l.exr"}, "--aov listlen: only"},
        BadValue{{"-o", "out.exr", "--aov", "depth=out.exr"},
                 "--aov depth: writes 'out.exr', the file -o writes"},
        BadValue{{"--aov", "depth=a.exr", "--aov", "primid=./a.exr"},
                 "--aov primid: writes './a.exr', the file --aov depth writes"},
        BadValue{{"-o", "s.png", "--stats-json", "s.png"}, "--stats-json: writes 's.png'"}));

// --spp beside --aa adaptive changes nothing: a warning, and the statistics say spp 1.
TEST(OptionValues, SppBesideAdaptiveSamplingIsWarnedAboutAndNotReported) {
  const std::string stats = test::tempPath("adaptive_spp.json");
  const test::CommandResult r = test::runCommand(
      {test::gridrtBinary(), "--width", "32", "--height", "24", "--aa", "adaptive", "--spp", "4",
       "-o", test::tempPath("adaptive_spp.png"), "--stats-json", stats});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("gridrt: warning: --spp 4 has no effect with --aa adaptive"),
            std::string::npos)
      << r.err;
  const std::string json = test::readWholeFile(stats);
  EXPECT_NE(json.find("\"spp\": 1"), std::string::npos) << json;
}

TEST(OptionValues, TheHelpShowsOneValuePerAov) {
  const std::string help = helpText();
  EXPECT_NE(help.find("--aov NAME[=FILE] "), std::string::npos) << help;
  EXPECT_EQ(help.find("NAME=FILE ..."), std::string::npos) << help;
}

TEST(OptionValues, GoodValuesPass) {
  EXPECT_EQ(usageError({"--spp", "4", "--fov", "35.5", "--ambient", "0", "--width", "32"}),
            "<accepted>");
}

// A camera the scene does not have is the command line's mistake: exit 2, like an
// unknown --device, for a file's cameras and for the built-in scene's.
TEST(OptionValues, AnUnknownCameraIsAUsageError) {
  for (const auto& scene : {std::string(), test::modelScene("bunny_res4.glb")}) {
    std::vector<std::string> argv{test::gridrtBinary(),        "--camera", "nope", "-q", "-o",
                                  test::tempPath("camera.png")};
    if (!scene.empty()) argv.push_back(scene);
    const test::CommandResult r = test::runCommand(argv);
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_NE(r.err.find("camera 'nope'"), std::string::npos) << r.err;
  }
}

// Outside a --crop window written full size, the id and depth AOVs hold their documented
// miss value -1 (0 would be triangle 0, PE 0, or a hit at distance 0).
TEST(OptionValues, ACroppedAovHoldsTheMissValueOutsideTheWindow) {
  const std::string id = test::tempPath("crop_id.exr"), depth = test::tempPath("crop_depth.exr");
  const test::CommandResult r = test::runCommand(
      {test::gridrtBinary(), "-q", "--width", "64", "--height", "48", "--crop", "16,12,48,36", "-o",
       test::tempPath("crop.exr"), "--aov", "primid=" + id, "--aov", "depth=" + depth});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const std::string& path : {id, depth}) {
    const ImageData image = readImage(path);
    int inside_hits = 0;
    for (int y = 0; y < image.height; ++y)
      for (int x = 0; x < image.width; ++x) {
        const float v = image.pixels[size_t(y * image.width + x)];
        const bool inside = x >= 16 && x < 48 && y >= 12 && y < 36;
        if (!inside) {
          EXPECT_EQ(v, -1.0f) << path << " at " << x << "," << y;
        }
        inside_hits += inside && v >= 0.0f;
      }
    EXPECT_EQ(inside_hits, 32 * 24) << path;  // the default scene's room fills the window
  }
}

}  // namespace
}  // namespace gridrt
