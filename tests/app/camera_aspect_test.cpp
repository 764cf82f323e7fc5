// A glTF camera's aspectRatio against the image's: the rays take the image's aspect (a
// square stays square whatever the file says), and an image given no size takes the
// camera's aspect at the default height.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "default_scene.h"
#include "gltf_writer.h"
#include "image_output.h"
#include "run_command.h"
#include "test_support.h"

namespace gridrt {
namespace {

// A 1 x 1 square facing a camera 4 units away whose file says aspectRatio 2.
std::string squareScene() {
  Scene scene;
  const int grey = shapes::addMaterial(scene, Material{});
  shapes::addRect(scene, {0, 0, 0}, {0.5f, 0, 0}, {0, 0.5f, 0}, grey);
  scene.camera.yfov = 0.5f;
  scene.camera.aspect = 2.0f;
  scene.camera.world = shapes::lookAtWorld({0, 0, 4}, {0, 0, 0});
  scene.has_camera = true;
  const std::string path = test::tempPath("square.gltf");
  writeGltf(scene, path);
  return path;
}

struct Extent {
  int width = 0, height = 0, columns = 0, rows = 0;
};

// The primitive-id AOV of a primary-only render, and the square's extent in pixels.
Extent renderSquare(const std::vector<std::string>& size_args) {
  const std::string id = test::tempPath("square_id.exr");
  std::vector<std::string> argv{
      test::gridrtBinary(),         squareScene(), "-q",          "--primary-only", "-o",
      test::tempPath("square.exr"), "--aov",       "primid=" + id};
  argv.insert(argv.end(), size_args.begin(), size_args.end());
  const test::CommandResult r = test::runCommand(argv);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  const ImageData image = readImage(id);
  Extent e{image.width, image.height, 0, 0};
  int x0 = image.width, x1 = -1, y0 = image.height, y1 = -1;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x)
      if (image.pixels[size_t(y * image.width + x)] >= 0) {
        x0 = std::min(x0, x), x1 = std::max(x1, x), y0 = std::min(y0, y), y1 = std::max(y1, y);
      }
  e.columns = x1 - x0 + 1;
  e.rows = y1 - y0 + 1;
  return e;
}

TEST(CameraAspect, ASquareStaysSquareWhateverTheFileSays) {
  for (const auto& size : std::vector<std::vector<std::string>>{
           {"--width", "240", "--height", "240"}, {"--width", "320", "--height", "240"}}) {
    const Extent e = renderSquare(size);
    SCOPED_TRACE(std::to_string(e.width) + "x" + std::to_string(e.height));
    EXPECT_GT(e.rows, 20);
    EXPECT_NEAR(e.columns, e.rows, 1);  // one pixel of rasterisation either way
  }
}

TEST(CameraAspect, AnImageGivenNoSizeTakesTheCamerasAspect) {
  const Extent e = renderSquare({});
  EXPECT_EQ(e.height, 480);
  EXPECT_EQ(e.width, 960);
  EXPECT_NEAR(e.columns, e.rows, 1);
  const Extent given = renderSquare({"--height", "100"});  // one dimension given: kept as is
  EXPECT_EQ(given.width, 640);
  EXPECT_EQ(given.height, 100);
}

}  // namespace
}  // namespace gridrt
