// Animated scenes on the command line (docs/animation.md): a frame of an animated scene is
// bit for bit the render of the same scene with that frame's pose baked into its nodes; a
// sequence of frames is bit for bit the single --time renders; one frame of a sequence with
// --crop (a render farm's task) is the single render's window; each frame is in
// --stats-json and the kernels are built once a run; bad animations and bad patterns fail
// with one line and write nothing.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "animated_test_scene.h"
#include "gltf_animation.h"
#include "gltf_loader.h"
#include "image_output.h"
#include "run_command.h"
#include "test_support.h"

namespace gridrt {
namespace {

namespace fs = std::filesystem;

// Small frames: the scene's every object covers some pixels at this size.
const std::vector<std::string> kSize = {"--width", "96", "--height", "72", "-q"};

test::CommandResult runGridrt(const std::vector<std::string>& args) {
  std::vector<std::string> argv{test::gridrtBinary()};
  argv.insert(argv.end(), args.begin(), args.end());
  argv.insert(argv.end(), kSize.begin(), kSize.end());
  return test::runCommand(argv);
}

void writeFile(const std::string& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

std::string animatedScene(const std::string& dir) {
  const std::string path = dir + "/animated.gltf";
  writeFile(path, test::makeAnimatedTestScene().animatedJson());
  return path;
}

// The test scene with its pose at t (all animations) baked into the nodes.
std::string bakedScene(const std::string& dir, double t) {
  const test::AnimatedTestScene scene = test::makeAnimatedTestScene();
  const std::string json = scene.animatedJson();
  const GltfDocument document = GltfDocument::fromMemory(
      reinterpret_cast<const unsigned char*>(json.data()), json.size(), "", "animated.gltf");
  std::vector<std::string> warnings;
  const std::vector<Animation> animations =
      readAnimations(document.model(), "animated.gltf", warnings);
  const ScenePose pose = poseAt(animations, chooseAnimations(animations, "", "animated.gltf"),
                                document.model().nodes.size(), t);
  const std::string path = dir + "/baked_" + std::to_string(t) + ".gltf";
  writeFile(path, scene.bakedJson(pose));
  return path;
}

// Whether two image files hold the same pixels, bit for bit.
bool samePixels(const std::string& a, const std::string& b) {
  const ImageData x = readImage(a), y = readImage(b);
  return x.width == y.width && x.height == y.height && x.channels == y.channels &&
         x.pixels.size() == y.pixels.size() &&
         std::memcmp(x.pixels.data(), y.pixels.data(), x.pixels.size() * sizeof(float)) == 0;
}

void expectRendered(const test::CommandResult& r, const std::string& what) {
  EXPECT_EQ(r.exit_code, 0) << what << ": " << r.err;
}

TEST(AnimationCli, AFrameEqualsItsPoseBakedIntoTheNodes) {
  const std::string dir = test::freshDir("anim_baked");
  const std::string animated = animatedScene(dir);
  for (double t : {0.3, 0.75}) {
    SCOPED_TRACE(t);
    const std::string baked = bakedScene(dir, t);
    const std::string a = dir + "/a.exr", b = dir + "/b.exr";
    const std::string a_id = dir + "/a_id.exr", b_id = dir + "/b_id.exr";
    expectRendered(
        runGridrt({animated, "--time", test::exactNumber(t), "-o", a, "--aov", "primid=" + a_id}),
        "animated");
    expectRendered(runGridrt({baked, "-o", b, "--aov", "primid=" + b_id}), "baked");
    EXPECT_TRUE(samePixels(a, b));
    EXPECT_TRUE(samePixels(a_id, b_id));
    // The pose matters: the still pose looks different.
    const std::string still = dir + "/still.exr";
    expectRendered(runGridrt({animated, "-o", still}), "still");
    EXPECT_FALSE(samePixels(a, still));
  }
}

TEST(AnimationCli, ASequenceEqualsSingleTimeRenders) {
  const std::string dir = test::freshDir("anim_sequence");
  const std::string scene = animatedScene(dir);
  const test::CommandResult r =
      runGridrt({scene, "--frames", "0:3", "--fps", "4", "-o", dir + "/seq_%02d.exr", "--aov",
                 "depth=" + dir + "/depth_%02d.exr"});
  expectRendered(r, "sequence");
  for (int k = 0; k <= 3; ++k) {
    SCOPED_TRACE(k);
    const std::string frame = dir + "/seq_0" + std::to_string(k) + ".exr";
    const std::string single = dir + "/single.exr", single_depth = dir + "/single_depth.exr";
    expectRendered(runGridrt({scene, "--time", test::exactNumber(k / 4.0), "-o", single, "--aov",
                              "depth=" + single_depth}),
                   "single");
    EXPECT_TRUE(samePixels(frame, single));
    EXPECT_TRUE(samePixels(dir + "/depth_0" + std::to_string(k) + ".exr", single_depth));
  }
  EXPECT_FALSE(samePixels(dir + "/seq_00.exr", dir + "/seq_03.exr"));
}

TEST(AnimationCli, OneCroppedFrameOfASequenceIsTheSingleRendersWindow) {
  // How a render farm asks for frame K of a sequence: --frames K:K with the crop of a tile.
  const std::string dir = test::freshDir("anim_farm");
  const std::string scene = animatedScene(dir);
  const std::vector<std::string> crop = {"--crop", "16,8,64,40", "--crop-output", "window"};
  std::vector<std::string> task = {
      scene, "--frames", "3:3", "--fps", "8", "-o", dir + "/tile_%04d.exr"};
  task.insert(task.end(), crop.begin(), crop.end());
  expectRendered(runGridrt(task), "task");
  std::vector<std::string> single = {scene, "--time", test::exactNumber(3.0 / 8.0), "-o",
                                     dir + "/single.exr"};
  single.insert(single.end(), crop.begin(), crop.end());
  expectRendered(runGridrt(single), "single");
  EXPECT_EQ(test::listDir(dir),
            (std::vector<std::string>{"animated.gltf", "single.exr", "tile_0003.exr"}));
  EXPECT_TRUE(samePixels(dir + "/tile_0003.exr", dir + "/single.exr"));
}

TEST(AnimationCli, StatisticsRecordEachFrameAndKernelsAreBuiltOnce) {
  const std::string dir = test::freshDir("anim_stats");
  const std::string scene = animatedScene(dir);
  auto stats = [&](const std::string& frames) {
    const std::string json = dir + "/stats.json";
    expectRendered(runGridrt({scene, "--frames", frames, "--fps", "10", "-o", dir + "/f_%d.png",
                              "--stats-json", json}),
                   frames);
    return nlohmann::json::parse(test::readWholeFile(json));
  };
  const nlohmann::json one = stats("0:0"), three = stats("4:6");
  EXPECT_EQ(three["animation_fps"], 10.0);
  ASSERT_EQ(three["frames"].size(), 3u);
  for (int i = 0; i < 3; ++i) {
    const nlohmann::json& f = three["frames"][size_t(i)];
    EXPECT_EQ(f["frame"], 4 + i);
    EXPECT_EQ(f["time"].get<double>(), (4 + i) / 10.0);
    EXPECT_EQ(f["output"], dir + "/f_" + std::to_string(4 + i) + ".png");
    EXPECT_EQ(f["triangles"], 20);
    EXPECT_GT(f["frame_ms"].get<double>(), 0.0);
    EXPECT_GT(f["rays"]["total"].get<double>(), 0.0);
  }
  EXPECT_EQ(three["frames_timed"], 3);
  // Three frames build (or load) the same programs as one.
  const int programs =
      one["programs"]["loaded"].get<int>() + one["programs"]["compiled"].get<int>();
  EXPECT_GT(programs, 0);
  EXPECT_EQ(three["programs"]["loaded"].get<int>() + three["programs"]["compiled"].get<int>(),
            programs);
}

TEST(AnimationCli, BadAnimationsFailWithOneLineAndWriteNothing) {
  const std::string dir = test::freshDir("anim_bad");
  // One triangle whose node's translation keys are both at time 0: not increasing.
  test::GltfDocumentBuilder b;
  const int times = b.floats({0, 0}, "SCALAR");
  const int values = b.floats({0, 0, 0, 1, 1, 1}, "VEC3");
  const int pos = b.floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3");
  const std::string json = b.json(
      "\"scenes\":[{\"nodes\":[0]}],\"nodes\":[{\"mesh\":0}],\"meshes\":[{"
      "\"primitives\":[{\"attributes\":{\"POSITION\":" +
      std::to_string(pos) + "}}]}],\"animations\":[{\"name\":\"Jump\",\"samplers\":[{\"input\":" +
      std::to_string(times) + ",\"output\":" + std::to_string(values) +
      "}],\"channels\":[{\"sampler\":0,\"target\":{\"node\":0,\"path\":"
      "\"translation\"}}]}]");
  const std::string scene = dir + "/bad.gltf";
  writeFile(scene, json);
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{"--time", "0.5", "-o", dir + "/out.png"},
        std::vector<std::string>{"--frames", "0:2", "-o", dir + "/out_%d.png"}}) {
    std::vector<std::string> all{scene};
    all.insert(all.end(), args.begin(), args.end());
    const test::CommandResult r = runGridrt(all);
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_EQ(r.err,
              "gridrt: " + scene +
                  ": animation 0 'Jump' sampler 0 (channel 0): input times do not increase: time "
                  "1 (0) after time 0 (0)\n");
    EXPECT_EQ(test::listDir(dir), std::vector<std::string>{"bad.gltf"});
  }
  // The still pose does not read the animations; it says they are there.
  const test::CommandResult still = test::runCommand(
      {test::gridrtBinary(), scene, "-o", dir + "/still.png", "--width", "16", "--height", "12"});
  EXPECT_EQ(still.exit_code, 0) << still.err;
  EXPECT_NE(still.err.find("warning: the scene has 1 animation(s); rendered in its still pose"),
            std::string::npos)
      << still.err;
}

TEST(AnimationCli, BadPatternsAreUsageErrorsAndWriteNothing) {
  const std::string dir = test::freshDir("anim_patterns");
  const std::string scene = animatedScene(dir);
  for (const std::vector<std::string>& outputs :
       {std::vector<std::string>{"-o", dir + "/out.png"},
        std::vector<std::string>{"-o", dir + "/out_%s.png"},
        std::vector<std::string>{"-o", dir + "/out_%d.png", "--aov", "depth=" + dir + "/d.exr"}}) {
    std::vector<std::string> args{scene, "--frames", "0:1"};
    args.insert(args.end(), outputs.begin(), outputs.end());
    const test::CommandResult r = runGridrt(args);
    EXPECT_EQ(r.exit_code, 2) << test::joinArgs(args);
    EXPECT_NE(r.err.find("is not a frame pattern for --frames"), std::string::npos) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  }
  EXPECT_EQ(test::listDir(dir), std::vector<std::string>{"animated.gltf"});
  const test::CommandResult unknown =
      runGridrt({scene, "--time", "0", "--animation", "Walk", "-o", dir + "/x.png"});
  EXPECT_EQ(unknown.exit_code, 2);
  EXPECT_NE(unknown.err.find("animation 'Walk' not found; available: 0 = 'Move', 1 = 'Deform'"),
            std::string::npos)
      << unknown.err;
  EXPECT_EQ(test::listDir(dir), std::vector<std::string>{"animated.gltf"});
  const test::CommandResult built_in =
      runGridrt({"--time", "0", "--animation", "0", "-o", dir + "/x.png"});
  EXPECT_EQ(built_in.exit_code, 2);
  EXPECT_EQ(built_in.err, "gridrt: --animation '0': the built-in scene has no animations\n");
  EXPECT_EQ(test::listDir(dir), std::vector<std::string>{"animated.gltf"});
}

TEST(AnimationCli, TheBuiltInSceneRendersTheSameAtAnyTime) {
  // No animations: --frames renders its still pose into every frame, with a warning.
  const std::string dir = test::freshDir("anim_builtin");
  const test::CommandResult r =
      test::runCommand({test::gridrtBinary(), "--frames", "0:1", "-o", dir + "/f_%d.exr", "--width",
                        "32", "--height", "24"});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("warning: the built-in scene has no animations"), std::string::npos)
      << r.err;
  const test::CommandResult still = test::runCommand(
      {test::gridrtBinary(), "-o", dir + "/still.exr", "--width", "32", "--height", "24"});
  EXPECT_EQ(still.exit_code, 0) << still.err;
  EXPECT_TRUE(samePixels(dir + "/f_0.exr", dir + "/still.exr"));
  EXPECT_TRUE(samePixels(dir + "/f_1.exr", dir + "/still.exr"));
}

}  // namespace
}  // namespace gridrt
