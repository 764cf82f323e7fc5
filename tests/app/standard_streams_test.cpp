// Standard streams: -o - writes the image to standard output (its format from --format,
// png by default) and nothing else goes there; --format must agree with a named file.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
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
using test::readWholeFile;
using test::runCommand;
using test::tempPath;

// gridrt with a small frame of the built-in scene and `args`.
std::vector<std::string> gridrt(const std::vector<std::string>& args) {
  std::vector<std::string> argv{test::gridrtBinary(), "--width", "32", "--height", "24"};
  argv.insert(argv.end(), args.begin(), args.end());
  return argv;
}

CommandResult expectSuccess(const std::vector<std::string>& argv,
                            const std::string& stdin_path = "/dev/null") {
  CommandResult r = runCommand(argv, stdin_path);
  EXPECT_EQ(r.exit_code, 0) << joinArgs(argv) << "\n" << r.err;
  return r;
}

// The bytes as a file, for reading them back as an image.
std::string saved(const std::string& bytes, const std::string& name) {
  const std::string path = tempPath(name);
  std::ofstream(path, std::ios::binary) << bytes;
  return path;
}

TEST(StandardOutput, ThePngOnStandardOutputIsTheFileAndNothingElse) {
  const std::string file = tempPath("file.png");
  expectSuccess(gridrt({"-q", "-o", file}));
  const std::string png = readWholeFile(file);
  ASSERT_GT(png.size(), 8u);
  EXPECT_EQ(expectSuccess(gridrt({"-q", "-o", "-"})).out, png);
  // Progress, the summary and the statistics table go to standard error.
  const CommandResult talkative = expectSuccess(gridrt({"-o", "-", "--stats", "-v"}));
  EXPECT_EQ(talkative.out, png);
  EXPECT_NE(talkative.err.find("triangles"), std::string::npos) << talkative.err;
  EXPECT_NE(talkative.err.find("-> standard output"), std::string::npos) << talkative.err;
}

TEST(StandardOutput, FormatNamesTheEncoding) {
  const std::string file = tempPath("file.exr");
  expectSuccess(gridrt({"-q", "-o", file}));
  const CommandResult exr = expectSuccess(gridrt({"-q", "-o", "-", "--format", "exr"}));
  ASSERT_EQ(exr.out.substr(0, 4), std::string("\x76\x2f\x31\x01", 4));  // OpenEXR's magic
  const ImageData want = readImage(file), got = readImage(saved(exr.out, "stdout.exr"));
  EXPECT_EQ(got.channels, want.channels);
  EXPECT_EQ(got.pixels, want.pixels);
  const CommandResult jpg = expectSuccess(gridrt({"-q", "-o", "-", "--format", "jpeg"}));
  EXPECT_EQ(jpg.out.substr(0, 3), "\xff\xd8\xff");
  EXPECT_EQ(readImage(saved(jpg.out, "stdout.jpg")).channels, 3);
}

TEST(StandardOutput, FormatMustAgreeWithANamedFile) {
  const std::string png = tempPath("agree.png");
  CommandResult r = runCommand(gridrt({"-q", "-o", png, "--format", "exr"}));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--format exr: -o '" + png + "' has another extension"), std::string::npos)
      << r.err;
  EXPECT_FALSE(fs::exists(png));
  expectSuccess(gridrt({"-q", "-o", tempPath("agree.jpeg"), "--format", "jpg"}));
  r = runCommand(gridrt({"-q", "-o", "-", "--format", "tif"}));
  EXPECT_EQ(r.exit_code, 2) << r.err;
  // Without -o the name the program chooses takes the format's extension.
  const std::string dir = test::freshDir("format_name");
  r = runCommand({"sh", "-c",
                  "cd '" + dir + "' && exec '" + test::gridrtBinary() +
                      "' -q --width 16 --height 12 --format exr"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(test::listDir(dir), std::vector<std::string>{"gridrt.exr"});
}

TEST(StandardOutput, CarriesTheImageAlone) {
  for (const auto& [args, message] : std::vector<std::pair<std::vector<std::string>, std::string>>{
           {{"-o", "-", "--stats-json", "-"}, "--stats-json -: standard output carries the image"},
           {{"-o", "-", "--frames", "0:1"}, "-o -: standard output takes one image"},
           {{"-o", tempPath("a.exr"), "--aov", "depth=-"}, "--aov depth: only -o"}}) {
    const CommandResult r = runCommand(gridrt(args));
    EXPECT_EQ(r.exit_code, 2) << joinArgs(args);
    EXPECT_NE(r.err.find(message), std::string::npos) << r.err;
    EXPECT_TRUE(r.out.empty());
  }
}

}  // namespace
}  // namespace gridrt
