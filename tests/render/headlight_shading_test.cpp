// Headlight shading (--primary-only, the paper's measurement): each pixel is its primary
// hit's base colour times |n . d| (n the shading normal, d the ray), and the background
// where the ray misses, computed here one pixel at a time from the frame's own AOVs.
#include <gtest/gtest.h>

#include <cmath>
#include <glm/glm.hpp>
#include <vector>

#include "camera_rays.h"
#include "default_scene.h"
#include "default_scene_fixture.h"
#include "gridrt_intersector.h"
#include "hit_surfaces.h"
#include "renderer.h"
#include "uniform_grid.h"

namespace gridrt {
namespace {

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

  std::vector<glm::vec3> geometric(scene_.triangleCount());
  for (size_t t = 0; t < geometric.size(); ++t) {
    const glm::vec3* v = &scene_.positions[3 * t];
    geometric[t] = glm::normalize(glm::cross(v[1] - v[0], v[2] - v[0]));
  }
  const std::vector<ShadingTriangle> smooth = makeShadingTriangles(scene_, geometric);
  ASSERT_FALSE(smooth.empty()) << "the default scene has vertex normals";
  size_t hits = 0, misses = 0, wrong = 0;
  for (int y = 0; y < settings.height; ++y)
    for (int x = 0; x < settings.width; ++x) {
      const size_t p = size_t(y) * settings.width + x;
      const glm::vec3 got(frame.film.rgb[3 * p], frame.film.rgb[3 * p + 1],
                          frame.film.rgb[3 * p + 2]);
      const int prim = int(frame.aovs.primid[p]);
      glm::vec3 want = settings.background;
      if (prim >= 0) {
        const GrRay r = cameraRay(camera, settings.width, settings.height, x, y, 0.5f, 0.5f);
        const HitSurface h = surfaceOfHit(smooth.data(), geometric.data(), prim, r.ox, r.oy, r.oz,
                                          r.dx, r.dy, r.dz, frame.aovs.depth[p]);
        const glm::vec3& base = scene_.materials[scene_.material_of[prim]].base_color;
        want = base * std::fabs(glm::dot(glm::vec3(h.nx, h.ny, h.nz), glm::vec3(r.dx, r.dy, r.dz)));
        ++hits;
      } else {
        ++misses;
      }
      wrong += glm::any(glm::greaterThan(glm::abs(got - want), glm::vec3(1e-6f)));
    }
  EXPECT_GT(hits, 1000u);
  EXPECT_GT(misses, 300u);
  EXPECT_EQ(wrong, 0u) << "of " << hits << " hits and " << misses << " misses";
}

}  // namespace
}  // namespace gridrt
