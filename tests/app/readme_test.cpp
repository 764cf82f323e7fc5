// The README's CLI reference is `gridrt --help` verbatim (tools/update_readme_cli.sh).
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "image_output.h"
#include "options.h"
#include "run_command.h"
#include "test_support.h"

namespace gridrt {
namespace {

TEST(Readme, CliReferenceEqualsHelpText) {
  std::ifstream in(test::sourcePath("README.md"));
  ASSERT_TRUE(in) << "README.md missing";
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
  EXPECT_EQ(block, help + "\n") << "run tools/update_readme_cli.sh";
}

// The README's picture is what the program renders: the command of
// tools/make_readme_images.sh, pixel for pixel (8-bit PNG codes decoded to floats).
TEST(Readme, DefaultPictureIsWhatTheProgramRenders) {
  const std::string fresh = test::tempPath("readme_default.png");
  const test::CommandResult r = test::runCommand({test::gridrtBinary(), "-q", "-o", fresh});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const ImageData want = readImage(fresh);
  const ImageData have = readImage(test::sourcePath("docs/images/default.png"));
  ASSERT_EQ(have.width, want.width);
  ASSERT_EQ(have.height, want.height);
  ASSERT_EQ(have.channels, want.channels);
  size_t differing = 0;
  for (size_t i = 0; i < want.pixels.size(); ++i) differing += have.pixels[i] != want.pixels[i];
  EXPECT_EQ(differing, 0u) << "run tools/make_readme_images.sh";
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
