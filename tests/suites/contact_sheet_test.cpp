// tools/contact_sheet.sh: every model of a folder rendered and laid out as one named sheet,
// a model that fails logged with its exit code and left blank; --help exits 0.
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <string>

#include "image_output.h"
#include "run_command.h"
#include "test_support.h"

namespace gridrt {
namespace {

TEST(ContactSheet, RendersEveryModelOfAFolderIntoOneSheetAndLogsFailures) {
  const std::string models = test::freshDir("models");
  for (const char* name : {"bunny_res4.glb", "teapot.glb"})
    std::ofstream(models + "/" + name, std::ios::binary)
        << test::readWholeFile(test::modelScene(name));
  std::ofstream(models + "/broken.gltf") << "{ not json";
  const std::string sheet = test::tempPath("sheet.png");
  setenv("GRIDRT", test::gridrtBinary().c_str(), 1);
  const test::CommandResult r =
      test::runCommand({test::sourcePath("tools/contact_sheet.sh"), models, sheet, "32", "2"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string log = test::readWholeFile(test::tempPath("sheet.log"));
  EXPECT_NE(log.find("bunny_res4\texit 0"), std::string::npos) << log;
  EXPECT_NE(log.find("teapot\texit 0"), std::string::npos) << log;
  EXPECT_NE(log.find("broken\texit 1"), std::string::npos) << log;
  // Three tiles of 32 pixels and a 16-pixel name strip, two columns: two rows.
  const ImageData image = readImage(sheet);
  EXPECT_GE(image.width, 2 * 32);
  EXPECT_GE(image.height, 2 * (32 + 16));
  EXPECT_LT(image.height, 3 * (32 + 16));
}

TEST(ContactSheet, HelpExitsZeroAndAMissingFolderIsAUsageError) {
  const test::CommandResult help =
      test::runCommand({test::sourcePath("tools/contact_sheet.sh"), "--help"});
  EXPECT_EQ(help.exit_code, 0);
  EXPECT_NE(help.out.find("contact_sheet.sh MODEL_DIR OUT.png"), std::string::npos) << help.out;
  const test::CommandResult missing = test::runCommand(
      {test::sourcePath("tools/contact_sheet.sh"), test::tempPath("nowhere"), "x.png"});
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_NE(missing.err.find("no folder"), std::string::npos) << missing.err;
}

}  // namespace
}  // namespace gridrt
