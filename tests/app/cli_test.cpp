// The gridrt command line, run as a subprocess: exit codes (0 success, 2 usage error, 1
// anything else), one-line "gridrt: " error messages that name the problem, and outputs
// that are never created (or clobbered) when a run fails.
//
// Set GRIDRT_CLI_VERBOSE=1 to print every invocation with its exit code and stderr.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <spawn.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "image_output.h"
#include "run_command.h"
#include "test_support.h"

namespace fs = std::filesystem;
using gridrt::test::base64;
using gridrt::test::bytesOf;
using gridrt::test::gridrtBinary;
using gridrt::test::modelScene;
using gridrt::test::tempPath;

namespace {

// ---------------------------------------------------------------------------------------------
// Running the binary

using RunResult = gridrt::test::CommandResult;

std::string readFile(const std::string& path) { return gridrt::test::readWholeFile(path); }

void writeFile(const std::string& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), std::streamsize(bytes.size()));
  ASSERT_TRUE(out.good()) << "cannot write fixture " << path;
}

std::string describe(const std::vector<std::string>& args) {
  std::string s = "gridrt";
  for (const auto& a : args) s += " " + a;
  return s;
}

// Runs build/gridrt with `args` (no shell: arguments are passed as they are), capturing
// stdout and stderr.
RunResult runGridrt(const std::vector<std::string>& args) {
  std::vector<std::string> argv{gridrtBinary()};
  argv.insert(argv.end(), args.begin(), args.end());
  RunResult r = gridrt::test::runCommand(argv);
  if (const char* v = std::getenv("GRIDRT_CLI_VERBOSE"); v && *v && *v != '0')
    std::cout << "[cli] " << describe(args) << "\n[cli]   exit " << r.exit_code
              << ", stderr: " << r.err << std::flush;
  return r;
}

// Fresh per-test directories: test_support.h.
std::string freshDir(const std::string& name) { return gridrt::test::freshDir("cli_" + name); }
using gridrt::test::listDir;

std::string lower(std::string s) {
  for (char& c : s) c = char(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

// The error contract: exit code, exactly one stderr line "gridrt: ...", naming `mention`.
void expectOneLineError(const RunResult& r, int expected_exit, const std::string& mention,
                        const std::string& what) {
  SCOPED_TRACE(what);
  EXPECT_EQ(r.signal, 0) << "gridrt was killed by signal " << r.signal << "; stderr: " << r.err;
  EXPECT_EQ(r.exit_code, expected_exit) << "stderr: " << r.err;
  EXPECT_EQ(r.err.rfind("gridrt: ", 0), 0u) << "stderr does not start with 'gridrt: ': " << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << "stderr is not one line: " << r.err;
  EXPECT_TRUE(!r.err.empty() && r.err.back() == '\n') << "stderr does not end a line: " << r.err;
  EXPECT_NE(r.err.find(mention), std::string::npos)
      << "stderr does not mention '" << mention << "': " << r.err;
  EXPECT_TRUE(r.out.empty()) << "unexpected stdout: " << r.out;
}

// Runs `args` plus "-o <dir>/out.png" (unless the arguments already name an output) in a
// fresh directory and checks the error contract, and that the directory stays empty: no
// output, no leftover temporary file.
RunResult expectFailure(const std::string& name, std::vector<std::string> args, int expected_exit,
                        const std::string& mention) {
  const std::string dir = freshDir(name);
  const std::string output = dir + "/out.png";
  bool has_output = std::find(args.begin(), args.end(), "-o") != args.end();
  if (!has_output) {
    args.push_back("-o");
    args.push_back(output);
  }
  RunResult r = runGridrt(args);
  expectOneLineError(r, expected_exit, mention, describe(args));
  EXPECT_FALSE(fs::exists(output)) << describe(args) << " created " << output;
  EXPECT_TRUE(listDir(dir).empty()) << describe(args) << " left files in " << dir;
  return r;
}

// ---------------------------------------------------------------------------------------------
// glTF fixtures

struct MeshSpec {
  std::vector<float> positions;   // xyz per vertex
  std::vector<uint16_t> indices;  // empty: non-indexed
  int mode = 4;                   // 4 triangles, 0 points
  int position_accessor = 0;      // override to make it dangle
};

// A one-mesh, one-node glTF with its buffer as a base64 data URI (camera and lights are the
// renderer's defaults).
std::string makeGltf(const MeshSpec& m) {
  std::string pos = bytesOf(m.positions);
  std::string idx = bytesOf(m.indices);
  std::string data = pos + idx;
  while (data.size() % 4) data.push_back('\0');
  const size_t vertices = m.positions.size() / 3;
  std::ostringstream j;
  j << R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],)";
  j << R"("meshes":[{"primitives":[{"attributes":{"POSITION":)" << m.position_accessor << "}";
  if (!m.indices.empty()) j << R"(,"indices":1)";
  j << R"(,"mode":)" << m.mode << "}]}],";
  j << R"("buffers":[{"byteLength":)" << data.size()
    << R"(,"uri":"data:application/octet-stream;base64,)" << base64(data) << R"("}],)";
  j << R"("bufferViews":[{"buffer":0,"byteOffset":0,"byteLength":)" << pos.size() << "}";
  if (!m.indices.empty())
    j << R"(,{"buffer":0,"byteOffset":)" << pos.size() << R"(,"byteLength":)" << idx.size() << "}";
  j << "],";
  j << R"("accessors":[{"bufferView":0,"componentType":5126,"count":)" << vertices
    << R"(,"type":"VEC3"})";
  if (!m.indices.empty())
    j << R"(,{"bufferView":1,"componentType":5123,"count":)" << m.indices.size()
      << R"(,"type":"SCALAR"})";
  j << "]}";
  return j.str();
}

// Two triangles forming a unit quad in the z=0 plane, facing +z.
MeshSpec quad() {
  MeshSpec m;
  m.positions = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
  m.indices = {0, 1, 2, 0, 2, 3};
  return m;
}

std::string writeFixture(const std::string& name, const std::string& content) {
  std::string path = tempPath(name);
  writeFile(path, content);
  return path;
}

// ---------------------------------------------------------------------------------------------
// Scene errors (exit 1)

TEST(Cli, MissingSceneFile) {
  std::string scene = tempPath("no_such_scene.gltf");
  fs::remove(scene);
  expectFailure("missing_scene", {scene}, 1, "no_such_scene.gltf");
}

TEST(Cli, DirectoryAsScene) {
  std::string dir = tempPath("scene_dir.gltf");
  fs::create_directories(dir);
  RunResult r = expectFailure("dir_scene", {dir}, 1, "scene_dir.gltf");
  EXPECT_NE(r.err.find("directory"), std::string::npos) << r.err;
}

TEST(Cli, GarbageGlb) {
  std::mt19937 rng(1234);
  std::string bytes(4096, '\0');
  for (char& c : bytes) c = char(rng() & 0xff);
  bytes[0] = 'x';  // never the 'glTF' magic by chance
  std::string scene = writeFixture("garbage.glb", bytes);
  expectFailure("garbage_glb", {scene}, 1, "garbage.glb");
}

TEST(Cli, GarbageGltf) {
  std::mt19937 rng(99);
  std::string bytes(4096, '\0');
  for (char& c : bytes) c = char(rng() & 0xff);
  bytes[0] = 'x';
  std::string scene = writeFixture("garbage.gltf", bytes);
  expectFailure("garbage_gltf", {scene}, 1, "garbage.gltf");
}

TEST(Cli, UnreadableSceneFile) {
  if (::geteuid() == 0) GTEST_SKIP() << "running as root: file permissions do not apply";
  std::string scene = writeFixture("unreadable.gltf", makeGltf(quad()));
  ASSERT_EQ(::chmod(scene.c_str(), 0), 0);
  expectFailure("unreadable", {scene}, 1, "unreadable.gltf");
  ::chmod(scene.c_str(), 0644);
}

TEST(Cli, TruncatedGlb) {
  std::string source = modelScene("bunny_res4.glb");
  ASSERT_TRUE(fs::exists(source)) << source;
  std::string bytes = readFile(source);
  ASSERT_GE(bytes.size(), 100u);
  std::string scene = writeFixture("truncated.glb", bytes.substr(0, 100));
  RunResult r = expectFailure("truncated_glb", {scene}, 1, "truncated.glb");
  EXPECT_NE(lower(r.err).find("truncated"), std::string::npos) << r.err;
}

TEST(Cli, WrongMagicGlb) {
  std::string json = makeGltf(quad());
  while (json.size() % 4) json.push_back(' ');
  auto u32 = [](uint32_t v) { return std::string(reinterpret_cast<const char*>(&v), 4); };
  std::string glb = "glTX" + u32(2) + u32(uint32_t(20 + json.size())) + u32(uint32_t(json.size())) +
                    "JSON" + json;
  std::string scene = writeFixture("wrong_magic.glb", glb);
  RunResult r = expectFailure("wrong_magic", {scene}, 1, "wrong_magic.glb");
  EXPECT_NE(r.err.find("magic"), std::string::npos) << r.err;
}

TEST(Cli, JsonSyntaxError) {
  std::string scene =
      writeFixture("syntax_error.gltf", R"({"asset": {"version": "2.0"}, "scenes": [ {,]})");
  expectFailure("json_syntax", {scene}, 1, "syntax_error.gltf");
}

TEST(Cli, AccessorIndexOutOfRange) {
  MeshSpec m = quad();
  m.position_accessor = 7;
  std::string scene = writeFixture("bad_accessor.gltf", makeGltf(m));
  expectFailure("bad_accessor", {scene}, 1, "bad_accessor.gltf");
}

TEST(Cli, IndexValueOutOfRange) {
  MeshSpec m = quad();
  m.indices = {0, 1, 2, 0, 2, 9};  // only 4 vertices
  std::string scene = writeFixture("bad_index.gltf", makeGltf(m));
  RunResult r = expectFailure("bad_index", {scene}, 1, "bad_index.gltf");
  EXPECT_NE(r.err.find("9"), std::string::npos) << r.err;
}

TEST(Cli, NoTriangles) {
  MeshSpec m = quad();
  m.indices.clear();
  m.mode = 0;  // points
  std::string scene = writeFixture("points_only.gltf", makeGltf(m));
  RunResult r = expectFailure("no_triangles", {scene}, 1, "points_only.gltf");
  EXPECT_NE(r.err.find("triangle"), std::string::npos) << r.err;
}

// One triangle with a NaN vertex is dropped with a warning; the rest renders.
TEST(Cli, NanVertexIsDroppedWithWarning) {
  MeshSpec m;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  m.positions = {0, 0, 0,    1,   0, 0,    1, 1, 0,      // fine
                 0, 0, 0,    1,   1, 0,    0, 1, 0,      // fine
                 0, 0, 0.5f, nan, 0, 0.5f, 0, 1, 0.5f};  // NaN x
  std::string scene = writeFixture("nan_vertex.gltf", makeGltf(m));
  const std::string dir = freshDir("nan_vertex");
  const std::string output = dir + "/nan.png";
  RunResult r = runGridrt({scene, "--width", "32", "--height", "24", "-o", output});
  EXPECT_EQ(r.signal, 0);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(fs::exists(output));
  bool found = false;
  std::istringstream lines(r.err);
  for (std::string line; std::getline(lines, line);)
    if (line.rfind("gridrt: warning: ", 0) == 0 && line.find("1 triangle") != std::string::npos &&
        line.find("NaN") != std::string::npos)
      found = true;
  EXPECT_TRUE(found) << "no warning naming 1 dropped NaN triangle; stderr:\n" << r.err;

  // -q silences the warning.
  RunResult quiet = runGridrt({scene, "--width", "32", "--height", "24", "-o", output, "-q"});
  EXPECT_EQ(quiet.exit_code, 0) << quiet.err;
  EXPECT_TRUE(quiet.err.empty()) << quiet.err;
}

// A failed run leaves an existing output file exactly as it was.
TEST(Cli, FailureLeavesExistingOutputUntouched) {
  const std::string dir = freshDir("existing_output");
  const std::string output = dir + "/keep.png";
  const std::string sentinel = "not really a png, but it must survive\n";
  writeFile(output, sentinel);
  std::string missing = tempPath("definitely_missing.glb");
  fs::remove(missing);

  for (const std::vector<std::string>& args :
       {std::vector<std::string>{missing, "-o", output},
        std::vector<std::string>{"--width", "0", "-o", output},
        std::vector<std::string>{"--device", "nosuchdevice", "-o", output, "--width", "8",
                                 "--height", "8"}}) {
    RunResult r = runGridrt(args);
    EXPECT_NE(r.exit_code, 0) << describe(args);
    EXPECT_EQ(r.signal, 0) << describe(args);
    EXPECT_EQ(readFile(output), sentinel) << describe(args) << " changed " << output;
    EXPECT_EQ(listDir(dir), std::vector<std::string>{"keep.png"})
        << describe(args) << " left files in " << dir;
  }
}

// ---------------------------------------------------------------------------------------------
// Usage errors (exit 2)

TEST(Cli, UnknownFlag) { expectFailure("unknown_flag", {"--frobnicate"}, 2, "--frobnicate"); }

TEST(Cli, WidthZero) { expectFailure("width_zero", {"--width", "0"}, 2, "--width"); }

TEST(Cli, WidthNotANumber) { expectFailure("width_abc", {"--width", "abc"}, 2, "--width"); }

TEST(Cli, NegativeSpp) { expectFailure("spp_negative", {"--spp", "-1"}, 2, "--spp"); }

TEST(Cli, GridZero) { expectFailure("grid_zero", {"--grid", "0,1,1"}, 2, "--grid"); }

TEST(Cli, GridBanana) {
  RunResult r = expectFailure("grid_banana", {"--grid", "banana"}, 2, "--grid");
  EXPECT_NE(r.err.find("banana"), std::string::npos) << r.err;
}

TEST(Cli, UnknownAccel) { expectFailure("accel_foo", {"--accel", "foo"}, 2, "--accel"); }

TEST(Cli, AovWithoutFile) { expectFailure("aov_no_eq", {"--aov", "depth"}, 2, "--aov"); }

TEST(Cli, UnknownAov) {
  std::string aov = tempPath("aov_bogus.exr");
  RunResult r = expectFailure("aov_bogus", {"--aov", "bogus=" + aov}, 2, "--aov");
  EXPECT_NE(r.err.find("bogus"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(aov));
}

TEST(Cli, BackgroundTwoComponents) {
  expectFailure("background_2", {"--background", "1,2"}, 2, "--background");
}

TEST(Cli, NegativeRayOffset) {
  expectFailure("ray_offset_neg", {"--ray-offset", "epsilon=-1"}, 2, "--ray-offset");
}

TEST(Cli, UnknownDevice) {
  RunResult probe = runGridrt({"--list-devices"});
  if (probe.exit_code == 1 && probe.err.find("no OpenCL") != std::string::npos)
    GTEST_SKIP() << "no OpenCL device on this machine: " << probe.err;
  RunResult r =
      expectFailure("unknown_device", {"--device", "nosuchdevice", "--width", "8", "--height", "8"},
                    2, "nosuchdevice");
  EXPECT_NE(r.err.find("available"), std::string::npos) << r.err;
}

// ---------------------------------------------------------------------------------------------
// Output errors (exit 1)

TEST(Cli, UnsupportedOutputExtension) {
  const std::string dir = freshDir("xyz_output");
  RunResult r = expectFailure("xyz_output_run", {"-o", dir + "/out.xyz"}, 1, "out.xyz");
  EXPECT_NE(r.err.find(".xyz"), std::string::npos) << r.err;
  EXPECT_TRUE(listDir(dir).empty());
}

TEST(Cli, OutputIntoMissingDirectory) {
  const std::string dir = freshDir("missing_dir_output");
  const std::string output = dir + "/no/such/dir/out.png";
  RunResult r = expectFailure("missing_dir_run", {"-o", output}, 1, "out.png");
  EXPECT_NE(r.err.find("does not exist"), std::string::npos) << r.err;
  EXPECT_TRUE(listDir(dir).empty());
}

TEST(Cli, OutputIsADirectory) {
  const std::string dir = freshDir("output_is_dir");
  fs::create_directories(dir + "/taken.png");
  RunResult r = runGridrt({"-o", dir + "/taken.png", "--width", "8", "--height", "8"});
  expectOneLineError(r, 1, "taken.png", "-o <directory>");
  EXPECT_TRUE(fs::is_directory(dir + "/taken.png"));
  EXPECT_EQ(listDir(dir), std::vector<std::string>{"taken.png"});
}

TEST(Cli, AovNotExr) {
  const std::string dir = freshDir("aov_png");
  RunResult r =
      expectFailure("aov_png_run", {"--aov", "depth=" + dir + "/depth.png"}, 1, "depth.png");
  EXPECT_TRUE(listDir(dir).empty());
}

// ---------------------------------------------------------------------------------------------
// Informational flags and a good run

TEST(Cli, ListDevices) {
  RunResult r = runGridrt({"--list-devices"});
  if (r.exit_code == 1 && r.err.find("no OpenCL") != std::string::npos)
    GTEST_SKIP() << "no OpenCL device on this machine: " << r.err;
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::istringstream lines(r.out);
  std::string header;
  ASSERT_TRUE(std::getline(lines, header)) << "no output";
  EXPECT_NE(header.find("name"), std::string::npos) << "header: " << header;
  EXPECT_NE(header.find("P:D"), std::string::npos) << "header: " << header;
  bool cpu_line = false;
  int device_lines = 0;
  for (std::string line; std::getline(lines, line);) {
    if (line.empty()) continue;
    ++device_lines;
    std::string l = lower(line);
    cpu_line |= l.find("pthread") != std::string::npos || l.find("cpu") != std::string::npos;
  }
  EXPECT_GE(device_lines, 1) << r.out;
  EXPECT_TRUE(cpu_line) << "no CPU/pthread device listed:\n" << r.out;
}

TEST(Cli, Version) {
  RunResult r = runGridrt({"--version"});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  ASSERT_EQ(r.out.rfind("gridrt ", 0), 0u) << r.out;
  std::string version = r.out.substr(7);
  ASSERT_FALSE(version.empty());
  EXPECT_TRUE(std::isdigit(static_cast<unsigned char>(version[0]))) << r.out;
  EXPECT_TRUE(r.err.empty()) << r.err;
}

TEST(Cli, Help) {
  RunResult r = runGridrt({"--help"});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("--accel"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("--width"), std::string::npos) << r.out;
  EXPECT_TRUE(r.err.empty()) << r.err;
}

TEST(Cli, GoodSmallRenderIsQuiet) {
  const std::string dir = freshDir("good_render");
  const std::string output = dir + "/small.png";
  RunResult r = runGridrt({"--width", "32", "--height", "24", "-o", output, "-q"});
  EXPECT_EQ(r.signal, 0);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(r.out.empty()) << r.out;
  EXPECT_TRUE(r.err.empty()) << r.err;
  ASSERT_TRUE(fs::exists(output));
  EXPECT_EQ(listDir(dir), std::vector<std::string>{"small.png"});
  gridrt::ImageData image = gridrt::readImage(output);
  EXPECT_EQ(image.width, 32);
  EXPECT_EQ(image.height, 24);
  EXPECT_EQ(image.channels, 3);
}

// Without -q a good run reports the device and a summary on stderr, all lines "gridrt: ".
TEST(Cli, GoodRenderReportsOnStderr) {
  const std::string dir = freshDir("good_render_verbose");
  const std::string output = dir + "/small.png";
  RunResult r = runGridrt({"--width", "16", "--height", "12", "-o", output});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(r.out.empty()) << r.out;
  EXPECT_TRUE(fs::exists(output));
  std::istringstream lines(r.err);
  int count = 0;
  for (std::string line; std::getline(lines, line); ++count)
    EXPECT_EQ(line.rfind("gridrt: ", 0), 0u) << line;
  EXPECT_GE(count, 1);
  EXPECT_NE(r.err.find("small.png"), std::string::npos) << r.err;
}

// Removes this process's temp directory (fixtures, outputs) when the tests end.
class TempDirCleanup : public ::testing::Environment {
 public:
  void TearDown() override {
    std::error_code ignored;
    fs::remove_all(fs::path(tempPath("cleanup")).parent_path(), ignored);
  }
};
const auto* const kCleanup = ::testing::AddGlobalTestEnvironment(new TempDirCleanup);

}  // namespace
