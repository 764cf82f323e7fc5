// Shading against closed-form values: Lambert under a point light, a mirror showing a
// known colour, Snell's law and Fresnel through a glass slab, total internal reflection.
#include "whitted_shading.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <glm/gtc/matrix_transform.hpp>
#include <memory>
#include <random>

#include "brute_intersector.h"
#include "camera_rays.h"
#include "cl_runtime.h"
#include "prepared_triangles.h"
#include "renderer.h"

namespace gridrt {
namespace {

constexpr float kPi = 3.14159265358979f;

void addQuad(Scene& s, glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 d, int material) {
  for (glm::vec3 v : {a, b, c, a, c, d}) s.positions.push_back(v);
  s.material_of.push_back(material);
  s.material_of.push_back(material);
}

class Shading : public ::testing::Test {
 protected:
  void SetUp() override {
    if (listDevices().empty()) GTEST_SKIP() << "no OpenCL device: install pocl-opencl-icd";
    runtime_ = std::make_unique<ClRuntime>("");
  }
  Frame render(const Scene& scene, const Camera& camera, RenderSettings settings) {
    auto tris = prepareTriangles(scene);
    BruteIntersector brute(*runtime_, tris);
    Renderer renderer(scene, camera, brute, settings);
    Frame frame;
    renderer.render(frame);
    return frame;
  }
  std::unique_ptr<ClRuntime> runtime_;
};

glm::vec3 pixel(const Frame& f, int i, int j) {
  size_t k = 3 * (size_t(j) * f.film.width + i);
  return {f.film.rgb[k], f.film.rgb[k + 1], f.film.rgb[k + 2]};
}

TEST_F(Shading, DiffuseQuadUnderAPointLightEqualsLambert) {
  Scene scene;
  Material grey;
  grey.base_color = glm::vec3(0.5f);
  grey.roughness = 1.0f;  // no Phong highlight
  scene.materials = {grey};
  addQuad(scene, {-1, 0, 1}, {1, 0, 1}, {1, 0, -1}, {-1, 0, -1}, 0);
  Light light;
  light.position = {0.2f, 1.0f, 0.1f};
  light.intensity = 2.0f;
  scene.lights = {light};
  scene.has_lights = true;
  Camera camera = lookAtCamera({0, 3, 0}, {0, 0, 0}, 0.6981317f);
  RenderSettings settings;
  settings.width = 64;
  settings.height = 48;
  const float ambient = 0.05f;
  settings.ambient = ambient;
  Frame frame = render(scene, camera, settings);
  int checked = 0;
  for (int j = 4; j < 48; j += 9)
    for (int i = 4; i < 64; i += 11) {
      GrRay r = cameraRay(camera, 64, 48, i, j, 0.5f, 0.5f);
      float t = -r.oy / r.dy;
      glm::vec3 p(r.ox + t * r.dx, 0.0f, r.oz + t * r.dz);
      if (std::fabs(p.x) > 0.99f || std::fabs(p.z) > 0.99f) continue;
      glm::vec3 to_light = light.position - p;
      float d2 = glm::dot(to_light, to_light);
      float cos_theta = to_light.y / std::sqrt(d2);
      float expected = 0.5f / kPi * light.intensity / d2 * cos_theta + ambient * 0.5f;
      EXPECT_NEAR(pixel(frame, i, j).r, expected, 1e-4f * expected) << i << "," << j;
      ++checked;
    }
  EXPECT_GT(checked, 10);
}

TEST_F(Shading, MirrorShowsTheColourItReflects) {
  // A 45-degree mirror under the camera reflects an emissive red wall; no lights.
  Scene scene;
  Material mirror;
  mirror.base_color = glm::vec3(1.0f);
  mirror.metallic = 1.0f;
  mirror.roughness = 0.0f;
  Material red;
  red.base_color = glm::vec3(0.0f);
  red.emissive = glm::vec3(0.9f, 0.1f, 0.0f);
  scene.materials = {mirror, red};
  // Mirror in the plane y = -z (normal (0,1,1)/sqrt2), seen from above (+Y).
  addQuad(scene, {-1, -1, 1}, {1, -1, 1}, {1, 1, -1}, {-1, 1, -1}, 0);
  // Red wall at z = -5 facing +Z... the mirror sends downward (-Y) rays towards +Z? No:
  // a ray going -Y reflects off normal (0,1,1)/sqrt2 into +Z, so the wall is at z = +5.
  addQuad(scene, {-10, -10, 5}, {10, -10, 5}, {10, 10, 5}, {-10, 10, 5}, 1);
  scene.has_lights = true;  // none
  Camera camera;
  camera.orthographic = true;
  camera.ymag = 0.5f;
  camera.world =
      glm::inverse(glm::lookAt(glm::vec3(0, 4, 0), glm::vec3(0, 0, 0), glm::vec3(0, 0, -1)));
  RenderSettings settings;
  settings.width = 16;
  settings.height = 16;
  settings.ambient = 0.0f;
  Frame frame = render(scene, camera, settings);
  for (int j = 0; j < 16; j += 5)
    for (int i = 0; i < 16; i += 5) {
      glm::vec3 c = pixel(frame, i, j);
      EXPECT_NEAR(c.r, 0.9f, 1e-5f);
      EXPECT_NEAR(c.g, 0.1f, 1e-5f);
      EXPECT_NEAR(c.b, 0.0f, 1e-5f);
    }
  settings.max_depth = 0;  // no reflection ray: the mirror alone is black
  frame = render(scene, camera, settings);
  EXPECT_NEAR(pixel(frame, 8, 8).r, 0.0f, 1e-6f);
}

TEST(SnellAndFresnel, RefractionObeysSnellsLaw) {
  const float eta = 1.0f / 1.5f;
  for (float deg : {0.0f, 10.0f, 30.0f, 45.0f, 60.0f, 85.0f}) {
    float a = deg * kPi / 180.0f;
    glm::vec3 d(std::sin(a), -std::cos(a), 0.0f);
    glm::vec3 out;
    ASSERT_TRUE(refractDirection(d, {0, 1, 0}, eta, out));
    float sin_t = std::sqrt(out.x * out.x + out.z * out.z);
    EXPECT_NEAR(sin_t, std::sin(a) * eta, 1e-5f) << deg;
    EXPECT_LT(out.y, 0.0f);
    EXPECT_NEAR(glm::length(out), 1.0f, 1e-5f);
  }
}

TEST(SnellAndFresnel, TotalInternalReflectionBeyondTheCriticalAngle) {
  const float eta = 1.5f;  // glass to air
  float critical = std::asin(1.0f / eta);
  glm::vec3 out;
  float below = critical - 0.01f, above = critical + 0.01f;
  EXPECT_TRUE(refractDirection({std::sin(below), -std::cos(below), 0}, {0, 1, 0}, eta, out));
  EXPECT_FALSE(refractDirection({std::sin(above), -std::cos(above), 0}, {0, 1, 0}, eta, out));
  EXPECT_EQ(fresnelDielectric(std::cos(above), eta), 1.0f);
  EXPECT_LT(fresnelDielectric(std::cos(below), eta), 1.0f);
}

TEST(SnellAndFresnel, NormalIncidenceReflectsFourPercentOffGlass) {
  EXPECT_NEAR(fresnelDielectric(1.0f, 1.0f / 1.5f), 0.04f, 1e-6f);
  EXPECT_NEAR(fresnelDielectric(1.0f, 1.5f), 0.04f, 1e-6f);
  EXPECT_NEAR(fresnelDielectric(0.0f, 1.0f / 1.5f), 1.0f, 1e-6f);  // grazing
}

// nextFloat is std::nextafter towards +-inf: zeros of both signs, denormals, the largest
// floats, infinities, NaN and a million random bit patterns.
TEST(NextFloat, EqualsNextafterEverywhere) {
  auto same = [](float a, float b) {
    return (std::isnan(a) && std::isnan(b)) || std::memcmp(&a, &b, sizeof a) == 0;
  };
  const float kMax = std::numeric_limits<float>::max();
  const float kDenorm = std::numeric_limits<float>::denorm_min();
  std::vector<float> values = {0.0f,
                               -0.0f,
                               kDenorm,
                               -kDenorm,
                               1.0f,
                               -1.0f,
                               kMax,
                               -kMax,
                               INFINITY,
                               -INFINITY,
                               NAN,
                               std::numeric_limits<float>::min(),
                               -std::numeric_limits<float>::min()};
  std::mt19937 rng(3);
  for (int k = 0; k < 1000000; ++k) {
    uint32_t bits = rng();
    float x;
    std::memcpy(&x, &bits, sizeof x);
    values.push_back(x);
  }
  int wrong = 0;
  for (float x : values)
    for (bool up : {false, true})
      wrong += !same(nextFloat(x, up), std::nextafter(x, up ? INFINITY : -INFINITY));
  EXPECT_EQ(wrong, 0);
}

// A glass slab (ior 1.5) tilted 45 degrees about the y axis in front of a wall that is red
// for x < 0 and green for x > 0. Seen by an orthographic camera along -Z, the slab shifts
// rays sideways by h*sin(ti - tt)/cos(tt) (h thickness); the red/green edge in the image
// must move by exactly that.
TEST_F(Shading, GlassSlabShiftsTheImageAsSnellPredicts) {
  Scene scene;
  Material glass;
  glass.base_color = glm::vec3(1.0f);
  glass.transmission = 1.0f;
  glass.roughness = 0.0f;
  glass.ior = 1.5f;
  Material red, green;
  red.base_color = green.base_color = glm::vec3(0.0f);
  red.emissive = {1, 0, 0};
  green.emissive = {0, 1, 0};
  scene.materials = {glass, red, green};
  const float h = 0.2f;
  // Slab faces: planes through the origin rotated 45 deg about y, thickness h along the normal.
  glm::vec3 n = glm::normalize(glm::vec3(1, 0, 1));
  glm::vec3 u = glm::normalize(glm::vec3(1, 0, -1)), v(0, 1, 0);
  auto corner = [&](float a, float b, float c) { return a * u * 3.0f + b * v * 3.0f + c * n; };
  // Front face (c = +h/2) faces +n, back face (c = -h/2) faces -n; sides close the box.
  addQuad(scene, corner(-1, -1, h / 2), corner(1, -1, h / 2), corner(1, 1, h / 2),
          corner(-1, 1, h / 2), 0);
  addQuad(scene, corner(-1, 1, -h / 2), corner(1, 1, -h / 2), corner(1, -1, -h / 2),
          corner(-1, -1, -h / 2), 0);
  addQuad(scene, {-10, -10, -3}, {0, -10, -3}, {0, 10, -3}, {-10, 10, -3}, 1);
  addQuad(scene, {0, -10, -3}, {10, -10, -3}, {10, 10, -3}, {0, 10, -3}, 2);
  scene.has_lights = true;  // none: only emission through the glass
  Camera camera;
  camera.orthographic = true;
  camera.ymag = 0.05f;  // with a 10:1 image: x in [-0.5, 0.5], 0.0025 per pixel
  camera.world = glm::translate(glm::mat4(1.0f), glm::vec3(0, 0, 5));
  RenderSettings settings;
  settings.width = 400;
  settings.height = 40;
  settings.ambient = 0.0f;
  Frame frame = render(scene, camera, settings);
  // Find the edge: the first column whose pixel is more green than red.
  int edge = -1;
  for (int i = 0; i < 400 && edge < 0; ++i)
    if (pixel(frame, i, 20).g > pixel(frame, i, 20).r) edge = i;
  ASSERT_GT(edge, 0);
  float ti = kPi / 4, tt = std::asin(std::sin(ti) / 1.5f);
  float shift = h * std::sin(ti - tt) / std::cos(tt);
  // The ray through the wall edge x = 0 entered at x = +-shift; the camera's x of column i.
  float half_width = 0.05f * 400.0f / 40.0f;
  float pixel_size = 2.0f * half_width / 400.0f;
  float edge_x = -half_width + edge * pixel_size;  // left side of the first green column
  EXPECT_NEAR(std::fabs(edge_x), shift, 1.0f * pixel_size)
      << "edge at x = " << edge_x << ", Snell predicts a shift of " << shift;
  EXPECT_GT(std::fabs(edge_x), 0.5f * shift);  // the slab really moved the edge
  // Energy through two interfaces at 45 degrees: (1 - F)^2 times the internal bounces.
  float f = fresnelDielectric(std::cos(ti), 1.0f / 1.5f);
  glm::vec3 c = pixel(frame, 80, 20);  // x = -0.3: red wall through the slab
  EXPECT_NEAR(c.r, (1 - f) * (1 - f), 0.01f);
}

// A concave corner (a floor meeting a wall, 1 m and 100 m from the origin) seen through a
// lens so narrow that neighbouring pixels are 1e-8 .. 1e-6 m apart: many hit points then
// round to just behind the other surface. Every point is lit (the light is in the room),
// so no pixel may show its ambient term alone; the renderer's shadow rays start at
// rayOffsetDistance (whitted_shading.h). Started at 0, the watertight test put 77 and 18
// of these pixels in false shadow (Moeller-Trumbore none here, some in
// ShadowSweep.ShadowRaysAtAConcaveCornerAreNotBlockedByTheOtherSurface).
TEST_F(Shading, ACornerSeenThroughANarrowLensIsLitUpToTheSeam) {
  struct View {
    float at, yfov;
  };
  for (const View view : {View{1.0f, 1e-6f}, View{100.0f, 3e-5f}}) {
    const glm::vec3 at(view.at);  // the seam runs through here, along z
    Scene scene;
    Material grey;
    grey.base_color = glm::vec3(0.5f);
    grey.roughness = 1.0f;
    scene.materials = {grey};
    addQuad(scene, at + glm::vec3(-1, 0, 1), at + glm::vec3(0.01f, 0, 1),
            at + glm::vec3(0.01f, 0, -1), at + glm::vec3(-1, 0, -1), 0);  // floor, past the wall
    addQuad(scene, at + glm::vec3(0, -0.01f, 1), at + glm::vec3(0, -0.01f, -1),
            at + glm::vec3(0, 1, -1), at + glm::vec3(0, 1, 1), 0);  // wall, below the floor
    Light light;
    light.position = at + glm::vec3(-0.5f, 0.6f, 0.2f);
    light.intensity = 2.0f;
    scene.lights = {light};
    scene.has_lights = true;
    const Camera camera = lookAtCamera(at + glm::vec3(-1.2f, 0.9f, 0.5f), at, view.yfov);
    RenderSettings settings;
    settings.width = 64;
    settings.height = 48;
    settings.max_depth = 0;
    settings.ambient = 0.05f;
    for (bool watertight : {false, true}) {
      const std::string where =
          std::string(watertight ? "watertight" : "mt") + " at " + std::to_string(view.at);
      const KernelOptions kernel{watertight};
      BruteIntersector brute(*runtime_, prepareTriangles(scene, kernel), kernel);
      Renderer renderer(scene, camera, brute, settings);
      Frame frame;
      renderer.render(frame);
      int dark = 0, seen = 0;
      for (int j = 0; j < settings.height; ++j)
        for (int i = 0; i < settings.width; ++i) {
          if (frame.aovs.primid[size_t(j) * settings.width + i] < 0) continue;
          ++seen;
          dark += pixel(frame, i, j).x < 2.0f * settings.ambient * grey.base_color.x;
        }
      EXPECT_GT(seen, settings.width * settings.height / 2) << where;
      EXPECT_EQ(dark, 0) << where << ": pixels in false shadow";
    }
  }
}

}  // namespace
}  // namespace gridrt
