// A scene from standard input: `gridrt -` reads a glTF (JSON) or GLB from standard input,
// renders it as it renders the same file (external files found in the current directory),
// reads it once for a sequence of frames, names its image gridrt.png by default, and ends
// with one line (no crash) for empty or malformed input.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "animated_test_scene.h"
#include "image_output.h"
#include "run_command.h"
#include "test_support.h"

namespace gridrt {
namespace {

namespace fs = std::filesystem;
using test::CommandResult;
using test::joinArgs;
using test::runCommand;

const std::vector<std::string> kSmall = {"-q", "--width", "48", "--height", "36"};

std::vector<std::string> gridrt(const std::vector<std::string>& args) {
  std::vector<std::string> argv{test::gridrtBinary()};
  argv.insert(argv.end(), args.begin(), args.end());
  argv.insert(argv.end(), kSmall.begin(), kSmall.end());
  return argv;
}

void expectSuccess(const std::vector<std::string>& argv, const std::string& stdin_path) {
  const CommandResult r = runCommand(argv, stdin_path);
  EXPECT_EQ(r.exit_code, 0) << joinArgs(argv) << " < " << stdin_path << "\n" << r.err;
}

// `argv` run by the shell in `dir`, standard input from `stdin_path`.
CommandResult runIn(const std::string& dir, const std::vector<std::string>& argv,
                    const std::string& stdin_path) {
  std::string line = "cd '" + dir + "' && exec";
  for (const std::string& a : argv) line += " '" + a + "'";
  return runCommand({"/bin/sh", "-c", line}, stdin_path);
}

void writeFile(const std::string& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary) << bytes;
}

// Whether two image files hold the same pixels, bit for bit.
bool samePixels(const std::string& a, const std::string& b) {
  const ImageData x = readImage(a), y = readImage(b);
  return x.width == y.width && x.height == y.height && x.channels == y.channels &&
         x.pixels.size() == y.pixels.size() && !x.pixels.empty() &&
         std::memcmp(x.pixels.data(), y.pixels.data(), x.pixels.size() * sizeof(float)) == 0;
}

TEST(StandardInput, AGlbOnStandardInputRendersAsTheFileBitForBit) {
  const std::string dir = test::freshDir("stdin_glb");
  const std::string scene = test::modelScene("bunny_res4.glb");
  for (const char* name : {"image.exr", "image.png"}) {
    const std::string from_file = dir + "/file_" + name, from_stdin = dir + "/stdin_" + name;
    expectSuccess(gridrt({scene, "-o", from_file, "--spp", "2"}), "/dev/null");
    expectSuccess(gridrt({"-", "-o", from_stdin, "--spp", "2"}), scene);
    EXPECT_TRUE(samePixels(from_file, from_stdin)) << name;
  }
  // The PNG's bytes too: nothing in it says where the scene came from.
  EXPECT_EQ(test::readWholeFile(dir + "/file_image.png"),
            test::readWholeFile(dir + "/stdin_image.png"));
}

TEST(StandardInput, AGltfFindsItsExternalFilesInTheCurrentDirectory) {
  const std::string dir = test::freshDir("stdin_gltf");
  // The animated scene as JSON whose buffer is the file "scene.bin" beside it: the bytes
  // of the buffer are the BIN chunk of the scene as a GLB.
  const test::AnimatedTestScene animated = test::makeAnimatedTestScene();
  const std::string glb = animated.buffer.glb("");
  uint32_t json_length = 0, bin_length = 0;
  std::memcpy(&json_length, glb.data() + 12, 4);
  std::memcpy(&bin_length, glb.data() + 20 + json_length, 4);
  writeFile(dir + "/scene.bin", glb.substr(28 + json_length, bin_length));
  const std::string rest = animated.animatedJson();
  const std::string data_uri = "data:application/octet-stream;base64,";
  const size_t uri = rest.find(data_uri), end = rest.find('"', uri);
  ASSERT_NE(uri, std::string::npos);
  writeFile(dir + "/scene.gltf", rest.substr(0, uri) + "scene.bin" + rest.substr(end));
  const CommandResult file = runIn(dir, gridrt({"scene.gltf", "-o", "file.exr"}), "/dev/null");
  ASSERT_EQ(file.exit_code, 0) << file.err;
  const CommandResult piped = runIn(dir, gridrt({"-", "-o", "stdin.exr"}), dir + "/scene.gltf");
  ASSERT_EQ(piped.exit_code, 0) << piped.err;
  EXPECT_TRUE(samePixels(dir + "/file.exr", dir + "/stdin.exr"));
  // Elsewhere the buffer is missing: one line naming standard input.
  const std::string other = test::freshDir("stdin_gltf_elsewhere");
  const CommandResult lost = runIn(other, gridrt({"-", "-o", "lost.exr"}), dir + "/scene.gltf");
  EXPECT_EQ(lost.exit_code, 1);
  EXPECT_EQ(lost.signal, 0);
  EXPECT_EQ(lost.err.rfind("gridrt: standard input", 0), 0u) << lost.err;
  EXPECT_EQ(std::count(lost.err.begin(), lost.err.end(), '\n'), 1) << lost.err;
}

TEST(StandardInput, ASequenceReadsTheSceneOnce) {
  const std::string dir = test::freshDir("stdin_frames");
  writeFile(dir + "/animated.gltf", test::makeAnimatedTestScene().animatedJson());
  expectSuccess(
      gridrt({dir + "/animated.gltf", "--frames", "0:2", "--fps", "4", "-o", dir + "/file_%d.exr"}),
      "/dev/null");
  expectSuccess(gridrt({"-", "--frames", "0:2", "--fps", "4", "-o", dir + "/stdin_%d.exr"}),
                dir + "/animated.gltf");
  for (int k = 0; k <= 2; ++k) {
    const std::string n = std::to_string(k);
    EXPECT_TRUE(samePixels(dir + "/file_" + n + ".exr", dir + "/stdin_" + n + ".exr")) << k;
  }
  EXPECT_FALSE(samePixels(dir + "/stdin_0.exr", dir + "/stdin_2.exr")) << "the scene moves";
}

TEST(StandardInput, TheDefaultOutputIsGridrtPng) {
  const std::string dir = test::freshDir("stdin_default_name");
  const CommandResult r = runIn(dir, gridrt({"-"}), test::modelScene("bunny_res4.glb"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(test::listDir(dir), std::vector<std::string>{"gridrt.png"});
  EXPECT_EQ(readImage(dir + "/gridrt.png").width, 48);
}

TEST(StandardInput, EmptyOrMalformedInputEndsWithOneLine) {
  const std::string dir = test::freshDir("stdin_bad");
  writeFile(dir + "/garbage", std::string("not a scene \x01\x02\xff", 16));
  writeFile(dir + "/truncated.glb",
            test::readWholeFile(test::modelScene("bunny_res4.glb")).substr(0, 100));
  for (const std::string& input :
       {std::string("/dev/null"), dir + "/garbage", dir + "/truncated.glb"}) {
    const CommandResult r = runCommand(gridrt({"-", "-o", dir + "/out.png"}), input);
    EXPECT_EQ(r.exit_code, 1) << input << ": " << r.err;
    EXPECT_EQ(r.signal, 0) << input;
    EXPECT_EQ(r.err.rfind("gridrt: standard input: ", 0), 0u) << input << ": " << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_FALSE(fs::exists(dir + "/out.png"));
  }
}

}  // namespace
}  // namespace gridrt
