// The glTF metallic-roughness BRDF (gltf_brdf.h) by the properties that pin it down: the
// GGX distribution integrates to 1 over the projected hemisphere, the BRDF is
// reciprocal, it never reflects more than it receives (a white furnace, integrated
// here), a black metal reflects nothing head on, and a mirror-smooth surface stays finite.
#include "gltf_brdf.h"

#include <gtest/gtest.h>

#include <cmath>

#include "default_scene.h"
#include "reference_intersector.h"
#include "renderer.h"
#include "run_command.h"

namespace gridrt {
namespace {

constexpr double kPi = 3.14159265358979323846;
// Midpoint sums of 20000 (and 400 x 400) steps: errors far below 1e-3 for these lobes.
constexpr double kIntegralTolerance = 1e-3;
// f(l, v) and f(v, l) are the same float operations in another order: a few ulps.
constexpr float kReciprocityTolerance = 1e-5f;

TEST(GltfBrdf, GgxDistributionIsNormalisedOverTheProjectedHemisphere) {
  for (float alpha : {0.1f, 0.5f, 1.0f}) {
    const int steps = 20000;
    double sum = 0.0;
    for (int i = 0; i < steps; ++i) {
      const double theta = (i + 0.5) / steps * kPi / 2;
      sum += ggxDistribution(float(std::cos(theta)), alpha) * std::cos(theta) * std::sin(theta);
    }
    EXPECT_NEAR(sum * (kPi / 2 / steps) * 2 * kPi, 1.0, kIntegralTolerance) << alpha;
  }
}

glm::vec3 direction(double theta, double phi) {
  return glm::vec3(float(std::sin(theta) * std::cos(phi)), float(std::sin(theta) * std::sin(phi)),
                   float(std::cos(theta)));
}

TEST(GltfBrdf, IsReciprocal) {
  const glm::vec3 n(0, 0, 1), a = direction(0.3, 0.2), b = direction(1.1, 2.5);
  for (float metallic : {0.0f, 1.0f})
    for (float roughness : {0.2f, 0.7f}) {
      const glm::vec3 ab = gltfBrdf({0.8f, 0.5f, 0.2f}, metallic, roughness, n, a, b);
      const glm::vec3 ba = gltfBrdf({0.8f, 0.5f, 0.2f}, metallic, roughness, n, b, a);
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(ab[c], ba[c], kReciprocityTolerance);
    }
}

// The reflected share of light from above, integrated over the viewing hemisphere.
double albedo(float metallic, float roughness, const glm::vec3& l) {
  const glm::vec3 n(0, 0, 1);
  const int steps = 400;
  double sum = 0.0;
  for (int i = 0; i < steps; ++i)
    for (int j = 0; j < steps; ++j) {
      const double theta = (i + 0.5) / steps * kPi / 2, phi = (j + 0.5) / steps * 2 * kPi;
      const glm::vec3 v = direction(theta, phi);
      sum += gltfBrdf(glm::vec3(1.0f), metallic, roughness, n, v, l).x * std::cos(theta) *
             std::sin(theta);
    }
  return sum * (kPi / 2 / steps) * (2 * kPi / steps);
}

TEST(GltfBrdf, AWhiteSurfaceNeverReflectsMoreThanItReceives) {
  const glm::vec3 l = direction(0.5, 0.0);
  for (float metallic : {0.0f, 1.0f})
    for (float roughness : {0.3f, 1.0f}) {
      const double a = albedo(metallic, roughness, l);
      EXPECT_LE(a, 1.0 + kIntegralTolerance) << metallic << " " << roughness;
      // Single scattering loses what bounces between microfacets: little of a smooth lobe.
      // (0.9993, 0.9728, 0.9891 and 0.3269 for the four here.)
      if (roughness < 0.5f) {
        EXPECT_GT(a, 0.9) << metallic << " " << roughness;
      }
    }
}

TEST(GltfBrdf, ABlackMetalReflectsNothingHeadOnAndABlackDielectricOnlyItsSpecularShare) {
  const glm::vec3 n(0, 0, 1), v = direction(0.4, 0.0), l = direction(0.4, kPi);
  // Head on, Schlick's term is F0 = the base colour: black. (At grazing angles it is not.)
  EXPECT_EQ(gltfBrdf(glm::vec3(0.0f), 1.0f, 0.5f, n, n, n), glm::vec3(0.0f));
  const glm::vec3 f = gltfBrdf(glm::vec3(0.0f), 0.0f, 0.5f, n, v, l);
  EXPECT_GT(f.x, 0.0f);
  EXPECT_EQ(f.x, f.y);  // grey: F0 = 0.04 in every channel
}

TEST(GltfBrdf, TransmissionTakesTheDiffuseLobe) {
  const glm::vec3 n(0, 0, 1), v = direction(0.4, 0.0), l = direction(0.9, 2.0);
  const glm::vec3 glass = gltfBrdf(glm::vec3(0.9f), 0.0f, 0.3f, n, v, l, 1.0f);
  const glm::vec3 black = gltfBrdf(glm::vec3(0.0f), 0.0f, 0.3f, n, v, l);
  EXPECT_EQ(glass, black);  // the specular lobe alone
  const glm::vec3 half = gltfBrdf(glm::vec3(0.9f), 0.0f, 0.3f, n, v, l, 0.5f);
  const glm::vec3 opaque = gltfBrdf(glm::vec3(0.9f), 0.0f, 0.3f, n, v, l);
  EXPECT_NEAR(half.x - black.x, 0.5f * (opaque.x - black.x), kReciprocityTolerance);
}

TEST(GltfBrdf, AMirrorSmoothSurfaceStaysFiniteInTheMirrorDirection) {
  const glm::vec3 n(0, 0, 1), v = direction(0.4, 0.0), l = direction(0.4, kPi);
  const glm::vec3 f = gltfBrdf(glm::vec3(1.0f), 1.0f, 0.0f, n, v, l);
  EXPECT_TRUE(std::isfinite(f.x) && f.x > 0.0f);
  EXPECT_EQ(gltfBrdf(glm::vec3(1.0f), 0.0f, 0.5f, n, -v, l), glm::vec3(0.0f));  // below
}

// --shading gltf: the renderer lights a hit with the BRDF times irradiance times n.l (a
// white quad under a directional light, seen head on), and Phong stays the default.
TEST(GltfBrdf, TheRendererShadesPunctualLightsWithItWhenAsked) {
  Scene scene;
  Material m;
  m.base_color = glm::vec3(0.7f);
  m.metallic = 0.0f;
  m.roughness = 0.6f;
  shapes::addRect(scene, {0, 0, 0}, {1, 0, 0}, {0, 1, 0}, shapes::addMaterial(scene, m));
  Light light;
  light.type = LightType::Directional;
  light.direction = -direction(0.6, 0.0);
  light.intensity = 2.0f;
  scene.lights.push_back(light);
  scene.has_lights = true;
  Camera camera;
  camera.orthographic = true;
  camera.xmag = camera.ymag = 0.5f;
  camera.world = shapes::lookAtWorld({0, 0, 3}, {0, 0, 0});
  ReferenceIntersector reference(scene);
  RenderSettings settings;
  settings.width = settings.height = 2;
  settings.max_depth = 0;
  auto render = [&](ShadingModel model) {
    settings.shading = model;
    Renderer renderer(scene, camera, reference, settings);
    Frame frame;
    renderer.render(frame);
    return frame.film.rgb[0];
  };
  const glm::vec3 n(0, 0, 1), l = direction(0.6, 0.0);
  const float direct = gltfBrdf(m.base_color, 0.0f, 0.6f, n, n, l).x * 2.0f * l.z;
  const float ambient = settings.ambient * surfaceTerms(m).diffuse.x;
  EXPECT_NEAR(render(ShadingModel::Gltf), ambient + direct, kReciprocityTolerance);
  EXPECT_NE(render(ShadingModel::Phong), render(ShadingModel::Gltf));
  EXPECT_EQ(RenderSettings{}.shading, ShadingModel::Phong);
}

TEST(GltfBrdf, AnUnknownShadingModelIsAUsageError) {
  const test::CommandResult r =
      test::runCommand({test::gridrtBinary(), "--shading", "pbr", "-o", test::tempPath("x.png")});
  EXPECT_EQ(r.exit_code, 2) << r.err;
}

}  // namespace
}  // namespace gridrt
