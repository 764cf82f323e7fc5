// docs/cli.md's reference is `gridrt --help` verbatim (tools/update_cli_reference.sh), and
// the README's picture is what the program renders.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include "image_output.h"
#include "options.h"
#include "run_command.h"
#include "test_support.h"

namespace gridrt {
namespace {

TEST(Readme, CliReferenceEqualsHelpText) {
  std::ifstream in(test::sourcePath("docs/cli.md"));
  ASSERT_TRUE(in) << "docs/cli.md missing";
  std::stringstream buffer;
  buffer << in.rdbuf();
  std::string readme = buffer.str();
  const std::string begin = "<!-- cli-begin -->\n```text\n", end = "```\n<!-- cli-end -->";
  size_t b = readme.find(begin), e = readme.find(end);
  ASSERT_NE(b, std::string::npos);
  ASSERT_NE(e, std::string::npos);
  std::string block = readme.substr(b + begin.size(), e - b - begin.size());
  std::string help = helpText();
  while (!help.empty() && help.back() == '\n') help.pop_back();
  EXPECT_EQ(block, help + "\n") << "run tools/update_cli_reference.sh";
}

// The README's picture is what the program renders: the command of
// tools/make_readme_images.sh, compared in 8-bit codes. On another CPU the host's libm
// (powf, expf through glibc's per-CPU variants) may round a shade one code differently, so
// a code of difference is allowed in a few pixels, and a larger one in a handful (an edge
// pixel whose hit another CPU's kernel compiler rounds the other way). A changed scene or
// shading moves far more: the picture left from before the walls met past their seams
// had 326 pixels one code off and 43 more than one (up to 255 codes).
TEST(Readme, DefaultPictureIsWhatTheProgramRenders) {
  constexpr float kOneCode = 1.0f / 255.0f;
  constexpr double kMaxOneCodePixels = 0.001;    // share of pixels that may be one code off
  constexpr double kMaxChangedPixels = 0.00005;  // share that may be off by more (15 here)
  const std::string fresh = test::tempPath("readme_default.png");
  const test::CommandResult r = test::runCommand({test::gridrtBinary(), "-q", "-o", fresh});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const ImageData want = readImage(fresh);
  const ImageData have = readImage(test::sourcePath("docs/images/default.png"));
  ASSERT_EQ(have.width, want.width);
  ASSERT_EQ(have.height, want.height);
  ASSERT_EQ(have.channels, want.channels);
  size_t one_code = 0, more = 0;
  const size_t channels = size_t(want.channels);
  for (size_t p = 0; p < want.pixels.size() / channels; ++p) {
    float worst = 0.0f;
    for (size_t c = 0; c < channels; ++c)
      worst =
          std::max(worst, std::fabs(have.pixels[p * channels + c] - want.pixels[p * channels + c]));
    more += worst > 1.5f * kOneCode;
    one_code += worst > 0.5f * kOneCode && worst <= 1.5f * kOneCode;
  }
  EXPECT_LE(double(more), kMaxChangedPixels * double(want.width) * double(want.height))
      << "pixels more than one code off: run tools/make_readme_images.sh";
  EXPECT_LE(double(one_code), kMaxOneCodePixels * double(want.width) * double(want.height))
      << "run tools/make_readme_images.sh";
}

// The README is for users: at most kMaxReadmeBytes, the rest lives in docs/.
TEST(Readme, StaysShort) {
  constexpr size_t kMaxReadmeBytes = 15000;
  std::ifstream in(test::sourcePath("README.md"), std::ios::binary | std::ios::ate);
  ASSERT_TRUE(in) << "README.md missing";
  EXPECT_LE(size_t(in.tellg()), kMaxReadmeBytes) << "move detail into docs/";
}

}  // namespace
}  // namespace gridrt
