// A scene without a camera or lights (a bare model, as converters write them) is framed
// from a three-quarter view and lit by a key and a fill light: the model fills the frame,
// its shading shows its shape, and it is neither washed out nor dark.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "camera_rays.h"
#include "default_lighting.h"
#include "default_scene.h"
#include "gltf_writer.h"
#include "image_output.h"
#include "run_command.h"
#include "test_support.h"

namespace gridrt {
namespace {

TEST(DefaultFraming, TheCameraLooksFromAThreeQuarterViewAndFitsTheBoundingSphere) {
  const Bounds b{{-1, -2, -3}, {3, 2, 1}};
  const Camera c = defaultCamera(b);
  const glm::vec3 eye(c.world[3]), towards_eye = glm::normalize(eye - b.center());
  EXPECT_GT(towards_eye.x, 0.3f);  // turned to the right
  EXPECT_GT(towards_eye.y, 0.3f);  // raised
  EXPECT_GT(towards_eye.z, 0.5f);  // still from the front
  const float radius = 0.5f * glm::length(b.extent());
  EXPECT_NEAR(glm::length(eye - b.center()) * std::sin(c.yfov / 2), radius, 1e-4f * radius);
  // Looks at the centre.
  EXPECT_NEAR(glm::dot(-glm::vec3(c.world[2]), -towards_eye), 1.0f, 1e-5f);
}

TEST(DefaultFraming, KeyAndFillLightsExposeAWhiteSurfaceAsDocumented) {
  const Camera c = defaultCamera(Bounds{{-1, -1, -1}, {1, 1, 1}});
  const std::vector<Light> lights = defaultLights(c);
  ASSERT_EQ(lights.size(), 2u);
  const float exposures[2] = {kKeyExposure, kFillExposure};
  for (int i = 0; i < 2; ++i) {
    // Irradiance pi * exposure, so white Lambert radiance = exposure.
    EXPECT_EQ(lights[size_t(i)].type, LightType::Directional);
    EXPECT_NEAR(lights[size_t(i)].intensity, 3.14159265f * exposures[i], 1e-5f);
    // Both arrive from the camera's side of the scene.
    EXPECT_LT(glm::dot(lights[size_t(i)].direction, glm::vec3(c.world[2])), 0.0f);
  }
}

// A white-ish sphere without camera or lights, rendered by the command line.
TEST(DefaultFraming, ABareSphereIsNeitherWashedOutNorDark) {
  Scene scene;
  Material white;
  white.base_color = glm::vec3(0.8f);
  shapes::addSphere(scene, {0, 0, 0}, 1.0f, 48, 24, shapes::addMaterial(scene, white));
  const std::string path = test::tempPath("bare_sphere.gltf"), out = test::tempPath("bare.exr");
  writeGltf(scene, path);
  const test::CommandResult r =
      test::runCommand({test::gridrtBinary(), path, "-q", "--width", "160", "--height", "120", "-o",
                        out, "--aov", "primid=" + test::tempPath("bare_id.exr")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const ImageData rgb = readImage(out), id = readImage(test::tempPath("bare_id.exr"));
  std::vector<float> luminance;
  for (size_t p = 0; p < id.pixels.size(); ++p)
    if (id.pixels[p] >= 0)
      luminance.push_back((rgb.pixels[3 * p] + rgb.pixels[3 * p + 1] + rgb.pixels[3 * p + 2]) / 3);
  // The box's bounding sphere (radius sqrt 3) fills the height: the sphere about 1/5 of it.
  ASSERT_GT(luminance.size(), id.pixels.size() / 8);
  std::sort(luminance.begin(), luminance.end());
  const float median = luminance[luminance.size() / 2], brightest = luminance.back();
  EXPECT_GT(median, 0.15f);                                       // not dark
  EXPECT_LT(brightest, 0.95f);                                    // nothing washed out to white
  EXPECT_GT(brightest - luminance[luminance.size() / 10], 0.3f);  // shading shows the shape
}

}  // namespace
}  // namespace gridrt
