// Headlight shading (--primary-only, the paper's measurement): each pixel is its primary
// hit's base colour times |n . d| (n the shading normal, d the ray), and the background
// where the ray misses, computed here one pixel at a time from the frame's own AOVs (the
// hit's triangle and t) in double precision: the hit point, its barycentrics in the
// triangle, the interpolated vertex normals, without the renderer's surface code.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <glm/glm.hpp>
#include <vector>

#include "camera_rays.h"
#include "default_scene.h"
#include "default_scene_fixture.h"
#include "gridrt_intersector.h"
#include "hit_surfaces.h"
#include "reference_intersector.h"
#include "renderer.h"
#include "uniform_grid.h"

namespace gridrt {
namespace {

// The renderer's float surface arithmetic against the double recomputation: 6.3e-7 at
// most here (with 0 the test fails); 1e-5 leaves room for other vector widths, far below
// what a wrong normal or weight changes (0.01 and more).
constexpr double kCosineTolerance = 1e-5;

// The unit shading normal at point p of triangle t: its vertex normals weighted by p's
// barycentrics (least squares in the triangle's plane), or the geometric normal when the
// scene has no vertex normals.
glm::dvec3 shadingNormal(const Scene& scene, size_t t, const glm::dvec3& p) {
  const glm::dvec3 a(scene.positions[3 * t]), b(scene.positions[3 * t + 1]),
      c(scene.positions[3 * t + 2]);
  const glm::dvec3 e1 = b - a, e2 = c - a, w = p - a;
  if (scene.normals.empty()) return glm::normalize(glm::cross(e1, e2));
  const double d11 = glm::dot(e1, e1), d12 = glm::dot(e1, e2), d22 = glm::dot(e2, e2);
  const double det = d11 * d22 - d12 * d12;
  const double b1 = (d22 * glm::dot(w, e1) - d12 * glm::dot(w, e2)) / det;
  const double b2 = (d11 * glm::dot(w, e2) - d12 * glm::dot(w, e1)) / det;
  const glm::dvec3 n = (1.0 - b1 - b2) * glm::dvec3(scene.normals[3 * t]) +
                       b1 * glm::dvec3(scene.normals[3 * t + 1]) +
                       b2 * glm::dvec3(scene.normals[3 * t + 2]);
  return glm::normalize(n);
}

class HeadlightShading : public test::DefaultSceneTest {};

TEST_F(HeadlightShading, EachPixelIsItsHitsBaseColourTimesCosineOrTheBackground) {
  const UniformGrid grid = buildUniformGrid(triangles_, sceneBounds(scene_), GridSettings{});
  GridRtIntersector gridrt(*runtime_, grid, PeInterrupt::CameraRays);
  // From outside the box, far enough back that its outline leaves a margin of misses.
  Camera camera = scene_.camera;
  camera.world = shapes::lookAtWorld({0.3f, 0.7f, 3.0f}, {0.0f, 0.5f, -1.0f});
  camera.yfov = 0.9f;
  RenderSettings settings;
  settings.width = 96;
  settings.height = 72;
  settings.primary_only = true;
  settings.background = {0.1f, 0.2f, 0.3f};
  settings.want_aovs = true;
  Renderer renderer(scene_, camera, gridrt, settings);
  Frame frame;
  renderer.render(frame);

  ASSERT_FALSE(scene_.normals.empty()) << "the default scene has vertex normals";
  size_t hits = 0, misses = 0, wrong = 0;
  double largest = 0.0;
  for (int y = 0; y < settings.height; ++y)
    for (int x = 0; x < settings.width; ++x) {
      const size_t p = size_t(y) * settings.width + x;
      const glm::dvec3 got(frame.film.rgb[3 * p], frame.film.rgb[3 * p + 1],
                           frame.film.rgb[3 * p + 2]);
      const int prim = int(frame.aovs.primid[p]);
      if (prim < 0) {
        ++misses;
        wrong += got != glm::dvec3(settings.background);  // exactly the background
        continue;
      }
      ++hits;
      const GrRay r = cameraRay(camera, settings.width, settings.height, x, y, 0.5f, 0.5f);
      const glm::dvec3 o(r.ox, r.oy, r.oz), d(r.dx, r.dy, r.dz);
      const glm::dvec3 n = shadingNormal(scene_, size_t(prim), o + double(frame.aovs.depth[p]) * d);
      const glm::dvec3 base(scene_.materials[scene_.material_of[prim]].base_color);
      const glm::dvec3 error = glm::abs(got - base * std::fabs(glm::dot(n, d)));
      const double e = std::max({error.x, error.y, error.z});
      largest = std::max(largest, e);
      wrong += e > kCosineTolerance;
    }
  EXPECT_GT(hits, 1000u);
  EXPECT_GT(misses, 300u);
  EXPECT_EQ(wrong, 0u) << "of " << hits << " hits and " << misses << " misses; largest error "
                       << largest;
  std::printf("largest error against the double recomputation: %.3g\n", largest);
}

// A quad whose base colour comes from a 4 x 4 texture and whose shading normal from a
// tilted normal map, beside one plain quad, seen at a slant: the shading's hits go 16 at a
// time through lanes, and the textures hit by hit, yet every pixel must be what the
// one-hit surface code (primarySurface, which fills the albedo and shading-normal AOVs)
// gives, bit for bit: albedo times |n . d| in the renderer's order of operations.
TEST(HeadlightShadingTextures, EachPixelIsTheOneHitSurfacesAlbedoTimesCosine) {
  Scene scene;
  Material textured;
  textured.base_color = {0.5f, 1.0f, 0.25f};
  textured.base_color_texture.texture = 0;
  textured.normal_texture.texture = 1;
  Material plain;
  plain.base_color = {0.9f, 0.3f, 0.6f};
  shapes::addRect(scene, {0.5f, 0.5f, 0.0f}, {0.5f, 0.0f, 0.0f}, {0.0f, 0.5f, 0.0f},
                  shapes::addMaterial(scene, textured));
  shapes::addRect(scene, {1.6f, 0.5f, 0.0f}, {0.5f, 0.0f, 0.0f}, {0.0f, 0.5f, 0.0f},
                  shapes::addMaterial(scene, plain));
  for (const glm::vec3& q : scene.positions) scene.texcoords[0].push_back({q.x, 1.0f - q.y});
  SceneImage colours, normals;
  TexelLevel level;
  level.width = level.height = 4;
  for (int t = 0; t < 16; ++t) level.texels.push_back({t / 15.0f, 1.0f - t / 15.0f, 0.5f, 1.0f});
  colours.colour.levels.push_back(level);
  TexelLevel tilt;
  tilt.width = tilt.height = 1;
  tilt.texels = {glm::vec4(0.8f, 0.4f, 0.9f, 1.0f)};  // tangent space (0.6, -0.2, 0.8)
  normals.data.levels.push_back(tilt);
  scene.images = {colours, normals};
  for (int image = 0; image < 2; ++image) {
    Texture texture;
    texture.image = image;
    texture.mag_filter = texture.min_filter = TextureFilter::Nearest;
    scene.textures.push_back(texture);
  }
  Camera camera;
  camera.world = shapes::lookAtWorld({-0.4f, 1.3f, 1.6f}, {1.0f, 0.5f, 0.0f});
  camera.yfov = 1.0f;
  ReferenceIntersector reference(scene);
  RenderSettings settings;
  settings.width = 77;  // not a multiple of 16: blocks of every fill
  settings.height = 53;
  settings.primary_only = true;
  settings.want_aovs = true;
  Renderer renderer(scene, camera, reference, settings);
  Frame frame;
  renderer.render(frame);

  size_t hits = 0, textured_hits = 0, tilted = 0, wrong = 0;
  for (int y = 0; y < settings.height; ++y)
    for (int x = 0; x < settings.width; ++x) {
      const size_t p = size_t(y) * settings.width + x;
      const int prim = frame.aovs.primid[p];
      if (prim < 0) continue;
      ++hits;
      textured_hits += scene.material_of[prim] == 0;
      const GrRay r = cameraRay(camera, settings.width, settings.height, x, y, 0.5f, 0.5f);
      const float* n = &frame.aovs.shading_normal[3 * p];
      const float* albedo = &frame.aovs.albedo[3 * p];
      tilted += std::fabs(n[2]) < 0.99f;
      const float cosine = std::fabs(dot3(n[0], n[1], n[2], r.dx, r.dy, r.dz));
      for (int c = 0; c < 3; ++c) wrong += frame.film.rgb[3 * p + c] != albedo[c] * cosine;
    }
  EXPECT_GT(textured_hits, 400u);
  EXPECT_GT(hits - textured_hits, 150u);
  EXPECT_GT(tilted, 400u) << "the normal map turns the textured quad's normals";
  EXPECT_EQ(wrong, 0u) << "channels of " << hits << " hits";
}

}  // namespace
}  // namespace gridrt
