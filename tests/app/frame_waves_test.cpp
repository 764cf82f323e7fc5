// The frame runs in waves of whole rows (--wave-rays) on the host's threads (--threads):
// neither may change a bit of the image or of the AOVs, which depend on the rays alone.
#include <gtest/gtest.h>

#include <cstring>
#include <string>
#include <vector>

#include "image_output.h"
#include "run_command.h"
#include "test_support.h"

namespace gridrt {
namespace {

struct Render {
  ImageData image, primid, pe;
};

// The default scene (mirrors, glass, two lights: every kind of ray) at 160x120.
Render renderWith(const std::string& name, const std::vector<std::string>& flags) {
  const std::string image = test::tempPath(name + ".exr"),
                    primid = test::tempPath(name + "_id.exr"),
                    pe = test::tempPath(name + "_pe.exr");
  std::vector<std::string> argv = test::gridrtCommand(
      "", 160, 120, {"-o", image, "--aov", "primid=" + primid, "--aov", "pe=" + pe});
  argv.erase(argv.begin() + 1);  // no scene: the built-in one
  argv.insert(argv.end(), flags.begin(), flags.end());
  const test::CommandResult r = test::runCommand(argv);
  EXPECT_EQ(r.exit_code, 0) << test::joinArgs(argv) << ": " << r.err;
  return {readImage(image), readImage(primid), readImage(pe)};
}

bool samePixels(const ImageData& a, const ImageData& b) {
  return a.width == b.width && a.height == b.height && a.channels == b.channels &&
         a.pixels.size() == b.pixels.size() &&
         std::memcmp(a.pixels.data(), b.pixels.data(), a.pixels.size() * sizeof(float)) == 0;
}

TEST(FrameWaves, WaveSizesAndThreadCountsGiveTheSameBits) {
  if (!test::gridrtHasDevice()) GTEST_SKIP() << "no OpenCL device";
  const Render one = renderWith("one_wave", {"--threads", "1"});
  ASSERT_GT(one.image.pixels.size(), 0u);
  // A row a wave (120 waves), an uneven split (7 rows: the last wave shorter), both cores.
  for (const auto& [name, flags] : std::vector<std::pair<std::string, std::vector<std::string>>>{
           {"row_waves", {"--wave-rays", "160", "--threads", "1"}},
           {"seven_row_waves_two_threads", {"--wave-rays", "1120", "--threads", "2"}},
           {"three_threads", {"--threads", "3"}}}) {
    const Render other = renderWith(name, flags);
    EXPECT_TRUE(samePixels(one.image, other.image)) << name << ": image";
    EXPECT_TRUE(samePixels(one.primid, other.primid)) << name << ": primid";
    EXPECT_TRUE(samePixels(one.pe, other.pe)) << name << ": pe";
  }
}

TEST(FrameWaves, AWaveOfNoRaysIsRefused) {
  const test::CommandResult r = test::runCommand({test::gridrtBinary(), "--wave-rays", "0"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--wave-rays"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace gridrt
