// The snapshot's command line (view_command.h): parsed back by gridrt's own parser it gives
// the options it was made from, to the bit; and the snapshot's file name.
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <sstream>

#include "errors.h"
#include "test_support.h"
#include "view_command.h"

namespace gridrt {
namespace {

// The words a POSIX shell makes of `line` (through sh itself: one word a line).
std::vector<std::string> shellWords(const std::string& line) {
  const std::string path = test::tempPath("words.txt");
  const std::string command = "sh -c 'for w in \"$@\"; do printf \"%s\\n\" \"$w\"; done' - " +
                              line + " > " + path;
  EXPECT_EQ(std::system(command.c_str()), 0) << command;
  std::ifstream in(path);
  std::vector<std::string> words;
  for (std::string w; std::getline(in, w);) words.push_back(w);
  return words;
}

Options parsed(const std::vector<std::string>& words) {
  std::vector<const char*> argv;
  for (const auto& w : words) argv.push_back(w.c_str());
  return *parseCommandLine(int(argv.size()), argv.data());
}

Options parsedLine(const std::string& line) { return parsed(shellWords(line)); }

// Every option commandLineOf writes, compared field by field.
void expectSamePicture(const Options& a, const Options& b) {
  EXPECT_EQ(a.scene, b.scene);
  EXPECT_EQ(a.width, b.width);
  EXPECT_EQ(a.height, b.height);
  EXPECT_EQ(a.spp, b.spp);
  EXPECT_EQ(a.max_depth, b.max_depth);
  EXPECT_EQ(a.accel, b.accel);
  EXPECT_EQ(a.grid.automatic, b.grid.automatic);
  EXPECT_EQ(a.grid.structure, b.grid.structure);
  EXPECT_EQ(a.grid.density, b.grid.density);
  EXPECT_EQ(a.grid.dims, b.grid.dims);
  EXPECT_EQ(a.watertight, b.watertight);
  EXPECT_EQ(a.primary_only, b.primary_only);
  EXPECT_EQ(a.shading, b.shading);
  EXPECT_EQ(a.background, b.background);
  EXPECT_EQ(a.ambient, b.ambient);
  EXPECT_EQ(a.ray_offset.robust, b.ray_offset.robust);
  EXPECT_EQ(a.ray_offset.epsilon, b.ray_offset.epsilon);
  EXPECT_EQ(a.adaptive_aa, b.adaptive_aa);
  EXPECT_EQ(a.aa_samples, b.aa_samples);
  EXPECT_EQ(a.aa_threshold, b.aa_threshold);
  EXPECT_EQ(a.min_path_weight, b.min_path_weight);
  EXPECT_EQ(a.alpha, b.alpha);
  EXPECT_EQ(a.camera_name, b.camera_name);
  EXPECT_EQ(a.eye, b.eye);
  EXPECT_EQ(a.target, b.target);
  EXPECT_EQ(a.fov_degrees, b.fov_degrees);
  EXPECT_EQ(a.time, b.time);
  EXPECT_EQ(a.animation, b.animation);
}

TEST(ViewCommand, ParsesBackToTheOptionsItWasMadeFrom) {
  const std::vector<std::vector<std::string>> commands = {
      {"gridrt"},
      {"gridrt", "scenes/models/bunny.glb", "--spp", "4", "--max-depth", "2", "--accel", "dda",
       "--grid", "8,9,10", "--intersector", "watertight", "--shading", "gltf", "--background",
       "0.1,0.2,0.3", "--ambient", "0.125", "--ray-offset", "epsilon=0.001", "--alpha",
       "--camera", "1", "--fov", "33.3", "--time", "0.1", "--animation", "walk",
       "--min-path-weight", "0.01"},
      {"gridrt", "a.glb", "--aa", "adaptive", "--aa-samples", "3", "--aa-threshold", "0.2",
       "--grid", "adaptive", "--grid-density", "0.3", "--primary-only", "--accel", "brute"},
  };
  for (const auto& words : commands) {
    Options o = parsed(words);
    // What the viewer sets: the window's size and a camera with awkward floats.
    o.width = 333, o.height = 111;
    o.eye = glm::vec3(0.1f, -1e-7f, 123456.789f);
    o.target = glm::vec3(std::nextafter(1.0f, 2.0f), 0.3f, -2.5f);
    const std::string line = commandLineOf(o);
    EXPECT_EQ(line.rfind("gridrt ", 0), 0u) << line;
    EXPECT_EQ(line.find(" -o"), std::string::npos) << line;
    SCOPED_TRACE(line);
    const Options back = parsedLine(line);
    expectSamePicture(o, back);
    EXPECT_EQ(commandLineOf(back), line);
  }
}

TEST(ViewCommand, LeavesOutWhatGivesTheSameImage) {
  const Options o = parsed({"gridrt", "--threads", "1", "--device", "0", "--wave-rays", "1000",
                            "--pe-layout", "lanes", "--transfer", "copy", "-q"});
  EXPECT_EQ(commandLineOf(o), "gridrt --width 640 --height 480");
}

TEST(ViewCommand, QuotesAScenePathForTheShell) {
  Options o = parsed({"gridrt", "my scene's (1).glb"});
  const std::string line = commandLineOf(o);
  EXPECT_EQ(shellWords(line).at(1), "my scene's (1).glb") << line;
}

TEST(ViewCommand, SnapshotTakesTheFirstFreeNumber) {
  const std::string dir = test::freshDir("snapshots");
  const Options bunny = parsed({"gridrt", "scenes/models/bunny.glb"});
  EXPECT_EQ(snapshotPath(bunny, dir), dir + "/bunny_view_0000.png");
  std::ofstream(dir + "/bunny_view_0000.png") << "x";
  std::ofstream(dir + "/bunny_view_0002.png") << "x";
  EXPECT_EQ(snapshotPath(bunny, dir), dir + "/bunny_view_0001.png");
  EXPECT_EQ(snapshotPath(parsed({"gridrt"}), dir), dir + "/gridrt_view_0000.png");
}

TEST(ViewOptions, RefusesWhatHasNoPlaceBesideAWindow) {
  for (const std::vector<std::string>& words :
       {std::vector<std::string>{"gridrt", "--view", "-o", "x.png"},
        {"gridrt", "--view", "--frames", "0:3"},
        {"gridrt", "--view", "--aov", "depth=d.exr"},
        {"gridrt", "--view", "--repeat", "3"},
        {"gridrt", "--view", "--crop", "0,0,8,8"},
        {"gridrt", "--view", "-"}}) {
    std::vector<const char*> argv;
    for (const auto& w : words) argv.push_back(w.c_str());
    const std::string error =
        test::errorOf<UsageError>([&] { parseCommandLine(int(argv.size()), argv.data()); });
    EXPECT_EQ(error.rfind("--view: ", 0), 0u) << words.back() << ": " << error;
  }
  EXPECT_TRUE(parsed({"gridrt", "--view", "--spp", "4"}).view);
}

}  // namespace
}  // namespace gridrt
