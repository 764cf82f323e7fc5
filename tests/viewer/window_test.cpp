// gridrt --view in a real window: Xvfb as the display, xdotool as the user, xwd as the
// eye. Each test starts the viewer on the built-in scene (small, so that a frame takes
// milliseconds), presses keys or drags, and checks what the viewer wrote and printed and
// what the window shows against the command line's own renders.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <glm/glm.hpp>
#include <memory>
#include <regex>
#include <sstream>

#include "animated_test_scene.h"
#include "image_output.h"
#include "run_command.h"
#include "test_support.h"
#include "view_camera.h"
#include "view_pictures.h"
#include "x_display.h"

namespace gridrt::test {
namespace {

// Generous waits: the first window of a run builds (or loads) the kernels.
constexpr double kWindowWaitS = 60.0;
constexpr double kOutputWaitS = 30.0;
// A camera angle read back from printed --look-at coordinates (nine digits each) and
// recomputed in float: a few float ulps of the coordinates, far below the 5 degrees of a key.
constexpr double kAngleToleranceDegrees = 1e-3;
constexpr int kWidth = 160, kHeight = 120;
// How long the window may take to show a frame again after the title announced it.
constexpr double kRedrawWaitS = 2.0;

std::unique_ptr<VirtualDisplay> display;
std::string skip_reason;

class ViewerWindow : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
#ifndef GRIDRT_HAS_WINDOW_MODULE
    skip_reason = "gridrt was built without its window module (SDL2: libsdl2-dev)";
    return;
#endif
    const std::string missing = missingXPrograms();
    if (!missing.empty()) {
      skip_reason = "needs " + missing + " (tools/setup.sh installs xvfb, xdotool, x11-apps)";
      return;
    }
    if (!gridrtHasDevice()) {
      skip_reason = "no OpenCL device";
      return;
    }
    display = std::make_unique<VirtualDisplay>();
    if (!display->started()) skip_reason = "no X server could start: " + display->failure();
  }
  static void TearDownTestSuite() { display.reset(); }
  void SetUp() override {
    if (!skip_reason.empty()) GTEST_SKIP() << skip_reason;
    dir_ = freshDir("view");
  }

  // The viewer on the built-in scene at kWidth x kHeight, then `args`; its window found.
  std::unique_ptr<ViewerProcess> start(const std::vector<std::string>& args = {}) {
    std::vector<std::string> all{"--width", std::to_string(kWidth), "--height",
                                 std::to_string(kHeight)};
    all.insert(all.end(), args.begin(), args.end());
    auto viewer = std::make_unique<ViewerProcess>(display->name(), dir_, all);
    window_ = viewer->waitForWindow(kWindowWaitS);
    EXPECT_FALSE(window_.empty()) << "no window: " << viewer->errorOutput();
    return viewer;
  }

  // The command line P printed, run with -o: its image's path.
  std::string renderPrinted(const std::string& command, const std::string& name,
                            const std::vector<std::string>& more = {}) {
    std::istringstream words(command);
    std::vector<std::string> argv;
    std::string word;
    words >> word;
    EXPECT_EQ(word, "gridrt") << command;
    argv.push_back(gridrtBinary());
    while (words >> word) argv.push_back(word);  // the built-in scene: no quoted words
    const std::string out = dir_ + "/" + name;
    argv.insert(argv.end(), {"-q", "-o", out});
    argv.insert(argv.end(), more.begin(), more.end());
    const CommandResult r = runCommand(argv);
    EXPECT_EQ(r.exit_code, 0) << joinArgs(argv) << ": " << r.err;
    return out;
  }

  // The window's pixels once its title says `title_part` (the frame after a snapshot).
  Screenshot windowPixels(ViewerProcess& viewer, const std::string& title_part) {
    EXPECT_FALSE(viewer.waitForTitle(title_part, kOutputWaitS).empty())
        << "the title never said '" << title_part << "'";
    return screenshot(display->name(), window_);
  }

  // The same, retried until it shows `want` or kRedrawWaitS pass (a resized window may be
  // drawn again by the server's exposure after the frame): the last screenshot.
  Screenshot windowShowing(ViewerProcess& viewer, const std::string& title_part,
                           const std::vector<unsigned char>& want) {
    Screenshot shot = windowPixels(viewer, title_part);
    for (int k = 0; shot.rgb != want && k < int(kRedrawWaitS / 0.05); ++k) {
      usleep(50000);
      shot = screenshot(display->name(), window_);
    }
    return shot;
  }

  std::string dir_, window_;
};

bool sameFileBytes(const std::string& a, const std::string& b) {
  const std::string x = readWholeFile(a), y = readWholeFile(b);
  return !x.empty() && x == y;
}

// The eye and target of a printed --look-at, false without one.
bool lookAtOfCommand(const std::string& command, LookAt& view) {
  static const std::regex look_at(R"(--look-at ([^ ,]+),([^ ,]+),([^ :]+):([^ ,]+),([^ ,]+),([^ ]+))");
  std::smatch m;
  if (!std::regex_search(command, m, look_at)) return false;
  float v[6];
  for (int i = 0; i < 6; ++i) v[i] = std::stof(m[i + 1].str());
  view = LookAt{{v[0], v[1], v[2]}, {v[3], v[4], v[5]}};
  return true;
}

// The angle between the eye's offsets from the target about +Y (degrees, counter-clockwise
// seen from above), and the change of its elevation.
double yawDegrees(const LookAt& a, const LookAt& b) {
  const glm::dvec3 u = glm::dvec3(a.eye - a.target), v = glm::dvec3(b.eye - b.target);
  const double turn = (std::atan2(v.x, v.z) - std::atan2(u.x, u.z)) * 180.0 / M_PI;
  return turn > 180.0 ? turn - 360.0 : turn <= -180.0 ? turn + 360.0 : turn;
}
double elevationDegrees(const LookAt& a) {
  const glm::dvec3 u = glm::dvec3(a.eye - a.target);
  return std::asin(u.y / glm::length(u)) * 180.0 / M_PI;
}

TEST_F(ViewerWindow, SnapshotIsTheCommandLinesImageBitForBitAndSoIsTheWindow) {
  auto viewer = start();
  ASSERT_FALSE(window_.empty());
  const std::string title = viewer->waitForTitle("sample 1/1", kOutputWaitS);
  EXPECT_EQ(title.rfind("gridrt", 0), 0u) << title;
  viewer->keys({"Left", "p"});
  const std::vector<std::string> lines = viewer->outputLines(1, kOutputWaitS);
  ASSERT_EQ(lines.size(), 1u) << viewer->errorOutput();
  EXPECT_EQ(lines[0].find(" -o"), std::string::npos) << lines[0];
  const std::string written = dir_ + "/gridrt_view_0000.png";
  ASSERT_TRUE(fileExists(written));
  const std::string rendered = renderPrinted(lines[0], "cli.png");
  EXPECT_TRUE(sameFileBytes(written, rendered)) << lines[0];
  const Screenshot cli = imageCodes(rendered);
  const Screenshot shown = windowShowing(*viewer, "wrote gridrt_view_0000.png", cli.rgb);
  ASSERT_EQ(shown.width, kWidth);
  ASSERT_EQ(shown.height, kHeight);
  EXPECT_TRUE(shown.rgb == cli.rgb) << "the window differs from " << rendered;
  viewer->keys({"q"});
  EXPECT_EQ(viewer->waitForExit(kOutputWaitS), 0) << viewer->errorOutput();
}

TEST_F(ViewerWindow, ArrowKeyAndDragTurnTheCameraByTheDocumentedAngles) {
  auto viewer = start();
  ASSERT_FALSE(window_.empty());
  viewer->waitForTitle("sample 1/1", kOutputWaitS);
  // Away from the scene's own camera first (its look-at is made from it), then one key,
  // then a drag of 40 pixels to the left and 20 down.
  viewer->keys({"Right", "p", "Left", "p"});
  viewer->xdotool("mousemove --window " + window_ + " 80 60 mousedown 1 mousemove_relative --sync -- -40 20 mouseup 1");
  viewer->keys({"p"});
  const std::vector<std::string> lines = viewer->outputLines(3, kOutputWaitS);
  ASSERT_EQ(lines.size(), 3u) << viewer->errorOutput();
  LookAt a, b, c;
  ASSERT_TRUE(lookAtOfCommand(lines[0], a)) << lines[0];
  ASSERT_TRUE(lookAtOfCommand(lines[1], b)) << lines[1];
  ASSERT_TRUE(lookAtOfCommand(lines[2], c)) << lines[2];
  // Left turns the eye clockwise seen from above by kOrbitDegreesPerKey; the target stays.
  EXPECT_NEAR(yawDegrees(a, b), -double(kOrbitDegreesPerKey), kAngleToleranceDegrees);
  EXPECT_NEAR(elevationDegrees(a), elevationDegrees(b), kAngleToleranceDegrees);
  EXPECT_EQ(a.target, b.target);
  // Dragging left turns it the other way, and down raises it: kOrbitDegreesPerPixel each.
  EXPECT_NEAR(yawDegrees(b, c), 40.0 * kOrbitDegreesPerPixel, kAngleToleranceDegrees);
  EXPECT_NEAR(elevationDegrees(c) - elevationDegrees(b), 20.0 * kOrbitDegreesPerPixel,
              kAngleToleranceDegrees);
  EXPECT_NEAR(glm::length(c.eye - c.target), glm::length(a.eye - a.target),
              1e-5 * glm::length(a.eye - a.target));
  viewer->keys({"Escape"});
  EXPECT_EQ(viewer->waitForExit(kOutputWaitS), 0) << viewer->errorOutput();
}

TEST_F(ViewerWindow, ViewKeysShowTheAovsHeatMaps) {
  auto viewer = start();
  ASSERT_FALSE(window_.empty());
  viewer->keys({"5", "p"});
  std::vector<std::string> lines = viewer->outputLines(1, kOutputWaitS);
  ASSERT_EQ(lines.size(), 1u) << viewer->errorOutput();
  const Screenshot pe_view = windowPixels(*viewer, "wrote gridrt_view_0000.png");
  viewer->keys({"7", "p"});
  lines = viewer->outputLines(2, kOutputWaitS);
  ASSERT_EQ(lines.size(), 2u) << viewer->errorOutput();
  const Screenshot list_view = windowPixels(*viewer, "wrote gridrt_view_0001.png");
  EXPECT_EQ(lines[0], lines[1]);  // a view changes what is shown, not the picture
  const std::string pe_exr = dir_ + "/pe.exr", list_exr = dir_ + "/listlen.exr";
  const std::string image = renderPrinted(
      lines[0], "aovs.png", {"--aov", "pe=" + pe_exr, "--aov", "listlen=" + list_exr});
  const ImageData pe = readImage(pe_exr), list = readImage(list_exr);
  ASSERT_EQ(pe.width * pe.height, kWidth * kHeight);
  // tools/heatmap.py's pictures of the files: each PE's hashed colour; viridis from 0 to
  // the largest list length.
  const size_t pixels = size_t(kWidth) * kHeight;
  float longest = 1.0f;
  for (size_t p = 0; p < pixels; ++p) longest = std::max(longest, list.pixels[p * list.channels]);
  Picture want_pe{kWidth, kHeight, std::vector<unsigned char>(pixels * 3)};
  Picture want_list = want_pe;
  for (size_t p = 0; p < pixels; ++p) {
    peColour(int32_t(std::lround(pe.pixels[p * pe.channels])), &want_pe.rgb[3 * p]);
    viridisColour(list.pixels[p * list.channels] / longest, &want_list.rgb[3 * p]);
  }
  EXPECT_TRUE(pe_view.rgb == want_pe.rgb) << "the pe view is not the pe AOV's colours";
  EXPECT_TRUE(list_view.rgb == want_list.rgb) << "the listlen view is not the listlen AOV's";
  EXPECT_FALSE(pe_view.rgb == imageCodes(image).rgb);
  viewer->keys({"q"});
  EXPECT_EQ(viewer->waitForExit(kOutputWaitS), 0) << viewer->errorOutput();
}

TEST_F(ViewerWindow, ResizingTheWindowChangesTheImageSize) {
  auto viewer = start();
  ASSERT_FALSE(window_.empty());
  viewer->waitForTitle("sample 1/1", kOutputWaitS);
  viewer->xdotool("windowsize --sync " + window_ + " 200 90");
  viewer->keys({"p"});
  const std::vector<std::string> lines = viewer->outputLines(1, kOutputWaitS);
  ASSERT_EQ(lines.size(), 1u) << viewer->errorOutput();
  EXPECT_NE(lines[0].find("--width 200 --height 90"), std::string::npos) << lines[0];
  const std::string rendered = renderPrinted(lines[0], "cli.png");
  EXPECT_TRUE(sameFileBytes(dir_ + "/gridrt_view_0000.png", rendered));
  const Screenshot cli = imageCodes(rendered);
  const Screenshot shown = windowShowing(*viewer, "wrote gridrt_view_0000.png", cli.rgb);
  ASSERT_EQ(shown.width, 200);
  ASSERT_EQ(shown.height, 90);
  EXPECT_TRUE(shown.rgb == cli.rgb);
  viewer->keys({"q"});
  EXPECT_EQ(viewer->waitForExit(kOutputWaitS), 0) << viewer->errorOutput();
}

TEST_F(ViewerWindow, AnimationStepsPlaysAndPausesFromTheGivenTime) {
  const std::string scene = dir_ + "/walk.gltf";
  std::ofstream(scene) << makeAnimatedTestScene().animatedJson();
  auto viewer = start({scene, "--time", "0.25", "-q"});
  ASSERT_FALSE(window_.empty());
  viewer->keys({"period", "p"});
  // Frame 7 at 24 fps (0.25 s is frame 6); seven frames back stop at frame 0.
  viewer->keys({"comma", "comma", "comma", "comma", "comma", "comma", "comma", "p"});
  const std::vector<std::string> lines = viewer->outputLines(2, kOutputWaitS);
  ASSERT_EQ(lines.size(), 2u) << viewer->errorOutput();
  const std::regex time(R"(--time ([^ ]+))");
  std::smatch m;
  ASSERT_TRUE(std::regex_search(lines[0], m, time)) << lines[0];
  EXPECT_EQ(std::stod(m[1].str()), 7.0 / 24.0) << lines[0];
  ASSERT_TRUE(std::regex_search(lines[1], m, time)) << lines[1];
  EXPECT_EQ(std::stod(m[1].str()), 0.0) << lines[1];
  // The posed scene's snapshot is the command line's image of that time.
  std::string command = lines[0];
  command.replace(command.find(scene), scene.size(), "SCENE");
  std::vector<std::string> argv{gridrtBinary()};
  std::istringstream words(command.substr(std::string("gridrt").size()));
  for (std::string w; words >> w;) argv.push_back(w == "SCENE" ? scene : w);
  argv.insert(argv.end(), {"-q", "-o", dir_ + "/cli.png"});
  EXPECT_EQ(runCommand(argv).exit_code, 0) << joinArgs(argv);
  EXPECT_TRUE(sameFileBytes(dir_ + "/walk_view_0000.png", dir_ + "/cli.png")) << lines[0];
  viewer->keys({"space"});
  EXPECT_FALSE(viewer->waitForTitle("(playing)", kOutputWaitS).empty());
  viewer->keys({"space", "q"});
  EXPECT_EQ(viewer->waitForExit(kOutputWaitS), 0) << viewer->errorOutput();
}

// A triangle seen by two camera nodes: C goes through them in order.
std::string twoCameraScene() {
  const std::vector<float> triangle{-1, -1, 0, 1, -1, 0, 0, 1, 0};
  return R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0,1,2]}],)"
         R"("nodes":[{"mesh":0},{"camera":0,"translation":[0,0,3]},)"
         R"({"camera":0,"translation":[0.5,0.2,3]}],)"
         R"("cameras":[{"type":"perspective","perspective":{"yfov":0.7,"znear":0.1}}],)"
         R"("meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],)"
         R"("accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3",)"
         R"("min":[-1,-1,0],"max":[1,1,0]}],"bufferViews":[{"buffer":0,"byteLength":36}],)"
         R"("buffers":[{"byteLength":36,"uri":"data:application/octet-stream;base64,)" +
         base64(bytesOf(triangle)) + R"("}]})";
}

TEST_F(ViewerWindow, CameraKeyCyclesTheGltfCamerasAndResetReturns) {
  const std::string scene = dir_ + "/two.gltf";
  std::ofstream(scene) << twoCameraScene();
  auto viewer = start({scene, "-q"});
  ASSERT_FALSE(window_.empty());
  viewer->keys({"c", "p", "c", "p", "Left", "r", "p"});
  const std::vector<std::string> lines = viewer->outputLines(3, kOutputWaitS);
  ASSERT_EQ(lines.size(), 3u) << viewer->errorOutput();
  EXPECT_NE(lines[0].find("--camera 1"), std::string::npos) << lines[0];
  EXPECT_NE(lines[1].find("--camera 0"), std::string::npos) << lines[1];
  // R: the scene's first camera as the command line gave it, no --camera, no --look-at.
  EXPECT_EQ(lines[2], "gridrt " + scene + " --width 160 --height 120");
  const std::string second = renderPrinted(lines[0], "second.png");
  EXPECT_TRUE(sameFileBytes(dir_ + "/two_view_0000.png", second));
  EXPECT_FALSE(sameFileBytes(dir_ + "/two_view_0001.png", second));
  viewer->keys({"q"});
  EXPECT_EQ(viewer->waitForExit(kOutputWaitS), 0) << viewer->errorOutput();
}

TEST(ViewerWithoutDisplay, SaysSoInOneLineAndExitsOne) {
  for (const std::string& display_value : {std::string(""), std::string(":9999")}) {
    // timeout: a viewer that found some other display would wait for input for ever.
    std::vector<std::string> argv{"timeout", "60", "env", "-u", "WAYLAND_DISPLAY"};
    if (display_value.empty())
      argv.insert(argv.end(), {"-u", "DISPLAY"});
    else
      argv.push_back("DISPLAY=" + display_value);
    argv.insert(argv.end(), {gridrtBinary(), "--view"});
    const CommandResult r = runCommand(argv);
    EXPECT_EQ(r.exit_code, 1) << display_value << ": " << r.err;
    EXPECT_EQ(r.err.rfind("gridrt: no display: ", 0), 0u) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  }
}

}  // namespace
}  // namespace gridrt::test
