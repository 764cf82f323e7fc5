// The README's CLI reference is `gridrt --help` verbatim (tools/update_readme_cli.sh).
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "options.h"
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

// The README is for users: at most kMaxReadmeBytes, the rest lives in docs/.
TEST(Readme, StaysShort) {
  constexpr size_t kMaxReadmeBytes = 15000;
  std::ifstream in(test::sourcePath("README.md"), std::ios::binary | std::ios::ate);
  ASSERT_TRUE(in) << "README.md missing";
  EXPECT_LE(size_t(in.tellg()), kMaxReadmeBytes) << "move detail into docs/";
}

}  // namespace
}  // namespace gridrt
