// Without -o the image is named after the scene (bunny.glb -> bunny.png, in the current
// folder; gridrt.png for the built-in scene), as POV-Ray and Mitsuba name theirs, and such
// a derived name never replaces an existing file unless --force; a name given with -o is
// the user's request and is written whether or not the file exists.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "run_command.h"
#include "test_support.h"

namespace gridrt {
namespace {

namespace fs = std::filesystem;

// gridrt run in `dir` with `args` (a small frame).
test::CommandResult runIn(const std::string& dir, const std::string& args) {
  return test::runCommand({"sh", "-c",
                           "cd '" + dir + "' && exec '" + test::gridrtBinary() +
                               "' -q --width 16 --height 12 " + args});
}

TEST(OutputNaming, TheImageIsNamedAfterTheScene) {
  const std::string dir = test::freshDir("naming");
  const test::CommandResult r = runIn(dir, "'" + test::modelScene("bunny_res4.glb") + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(fs::exists(dir + "/bunny_res4.png"));
  EXPECT_FALSE(fs::exists(dir + "/gridrt.png"));
  ASSERT_EQ(runIn(dir, "").exit_code, 0);  // the built-in scene
  EXPECT_TRUE(fs::exists(dir + "/gridrt.png"));
}

TEST(OutputNaming, ADerivedNameReplacesNothingWithoutForce) {
  const std::string dir = test::freshDir("naming_force");
  const std::string scene = "'" + test::modelScene("bunny_res4.glb") + "'";
  ASSERT_EQ(runIn(dir, scene).exit_code, 0);
  const auto written = fs::last_write_time(dir + "/bunny_res4.png");
  const test::CommandResult again = runIn(dir, scene);
  EXPECT_EQ(again.exit_code, 2);
  EXPECT_NE(again.err.find("'bunny_res4.png' exists: replace it with --force"), std::string::npos)
      << again.err;
  EXPECT_EQ(fs::last_write_time(dir + "/bunny_res4.png"), written);  // untouched
  EXPECT_EQ(runIn(dir, scene + " --force").exit_code, 0);
  EXPECT_EQ(runIn(dir, scene + " -o bunny_res4.png").exit_code, 0);  // named: replaced
}

}  // namespace
}  // namespace gridrt
