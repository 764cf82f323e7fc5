// Light culling (host/gridrt/culling/light_culling.h): wherever the ray/triangle test reports a
// hit for a shadow ray towards a light, the ray's (a, b) on its cube face's frame lies inside the
// triangle's box seen from the light, also for rays whose line misses the light and hits the test's
// rounding lets through just outside the triangle; triangles edge-on to the light or beside it are
// never culled; the boxes are made again only when a batch outgrows them; and shadow rays traced
// through the light bundles hit what brute force hits, with fewer tests than segment culling.
#include "light_culling.h"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <random>

#include "brute_intersector.h"
#include "camera_rays.h"
#include "cl_runtime.h"
#include "default_scene.h"
#include "gridrt_intersector.h"
#include "light_bundles.h"
#include "prepared_triangles.h"
#include "test_support.h"
#include "uniform_grid.h"

namespace gridrt {
namespace {

// The cube face of a direction from the light, as the light bundles choose it.
int faceOf(const glm::vec3& w) {
  const glm::vec3 m = glm::abs(w);
  const int a = m.x >= m.y && m.x >= m.z ? 0 : (m.y >= m.z ? 1 : 2);
  return 2 * a + (w[a] < 0.0f);
}

bool inside(const CullBox& box, float a, float b) {
  return a >= box.amin && a <= box.amax && b >= box.bmin && b <= box.bmax;
}

struct Violations {
  size_t hits = 0;     // hits (0 < t < tmax) on triangles with a finite box
  size_t outside = 0;  // ... whose lane lies outside the box
};

// Random triangles around a light at 40 units from the origin (a third of them slivers, a
// third close to the light), shadow rays from points beyond each triangle towards the light
// through its vertices and edges with a tiny random miss, where the test's rounding decides;
// half the rays end up to 1/1000 of their length beside the light (`jitter`), as rays from
// offset origins do.
Violations countViolations(bool with_miss) {
  std::mt19937 rng(2718);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  Violations result;
  for (int trial = 0; trial < 600; ++trial) {
    // Every other scene far from the origin, where the test's rounding grows with |o|.
    const glm::vec3 light =
        trial % 2 ? glm::vec3(30.0f, 25.0f, -10.0f) : glm::vec3(3000.0f, 2500.0f, -1000.0f);
    const float distance =
        trial % 3 == 2 ? 0.5f + std::abs(unit(rng)) : 5.0f + 20.0f * std::abs(unit(rng));
    const glm::vec3 centre =
        light + glm::normalize(glm::vec3(unit(rng), unit(rng), unit(rng))) * distance;
    glm::vec3 v[3];
    const float size = 0.2f * distance;
    for (glm::vec3& x : v) x = centre + glm::vec3(unit(rng), unit(rng), unit(rng)) * size;
    if (trial % 3 == 0) v[2] = v[0] + (v[1] - v[0]) * 0.5f + (v[2] - v[0]) * 0.01f;
    const GrTriangle tri = prepareTriangle(v, 0);
    std::vector<GrRay> rays;
    for (int ray = 0; ray < 1000; ++ray) {
      const float scale = std::ldexp(1.0f, -10 - int(rng() % 14)) * size;
      const float along = (ray / 3) % 2 ? 0.0f : std::abs(unit(rng));  // vertex or edge
      const glm::vec3 aim = v[ray % 3] + along * (v[(ray + 1) % 3] - v[ray % 3]) +
                            glm::vec3(unit(rng), unit(rng), unit(rng)) * scale;
      const glm::vec3 origin = light + (aim - light) * (1.2f + 2.0f * std::abs(unit(rng)));
      const float jitter = ray % 2 ? 1e-3f * glm::length(origin - light) : 0.0f;
      const glm::vec3 end = light + glm::vec3(unit(rng), unit(rng), unit(rng)) * jitter;
      const glm::vec3 d = glm::normalize(end - origin);
      rays.push_back(
          GrRay{origin.x, origin.y, origin.z, 0.0f, d.x, d.y, d.z, glm::length(end - origin)});
    }
    // The batch's bounds, as the light bundles measure them.
    TowardsOrigin towards;
    for (const GrRay& r : rays) {
      if (with_miss) towards.miss = std::max(towards.miss, double(missOfLight(r, light)));
      towards.ray_reach = std::max(
          towards.ray_reach, double(std::abs(r.ox) + std::abs(r.oy) + std::abs(r.oz) + r.tmax));
      towards.min_length =
          std::min(towards.min_length, double(glm::length(glm::vec3(r.dx, r.dy, r.dz))));
    }
    std::vector<CullBox> boxes[6];
    for (int f = 0; f < 6; ++f)
      computeTowardsOriginBoxes(cubeFaceFrame(f), light, towards, {tri}, boxes[f]);
    for (const GrRay& r : rays) {
      const glm::vec3 o(r.ox, r.oy, r.oz), d(r.dx, r.dy, r.dz);
      float t, u, w;
      if (!test::intersectScalar(tri, o, d, &t, &u, &w) || !(t > 0.0f) || !(t < r.tmax)) continue;
      const int face = faceOf(-d);
      const CullBox& box = boxes[face][0];
      if (std::isinf(box.amax)) continue;
      ++result.hits;
      float a, b;
      cullCoordinates(cubeFaceFrame(face), d.x, d.y, d.z, a, b);
      result.outside += !inside(box, a, b);
    }
  }
  return result;
}

TEST(LightCulling, MarginCoversRaysThatMissTheLightAndTheTestsRounding) {
  const Violations with = countViolations(true);
  EXPECT_GT(with.hits, 100000u);
  EXPECT_EQ(with.outside, 0u);
  // Boxes not grown by the rays' miss of the light: the rays that end beside it fall outside.
  // (The test's rounding from the rays' own origins, the other term, is the bound of
  // segment culling, whose own test shows its factor needed: SegmentCulling.MarginCovers...)
  const Violations without = countViolations(false);
  EXPECT_GT(without.outside, 0u);
}

TEST(LightCulling, TrianglesEdgeOnOrBesideTheLightAreNeverCulled) {
  const glm::vec3 light(0.0f, 0.0f, 0.0f);
  TowardsOrigin towards;
  towards.ray_reach = 20.0;
  const GrCullFrame down = cubeFaceFrame(3);  // -y
  std::vector<CullBox> boxes;
  auto boxOf = [&](glm::vec3 a, glm::vec3 b, glm::vec3 c) {
    const glm::vec3 v[3] = {a, b, c};
    computeTowardsOriginBoxes(down, light, towards, {prepareTriangle(v, 0)}, boxes);
    return boxes[0];
  };
  const CullBox facing = boxOf({-1, -5, -1}, {1, -5, -1}, {0, -5, 1});
  EXPECT_TRUE(std::isfinite(facing.amin) && std::isfinite(facing.amax));
  EXPECT_LT(facing.amax - facing.amin, 1.0f);
  // The light in the triangle's plane: every ray through it grazes.
  const CullBox edge_on = boxOf({0, -5, -1}, {0, -5, 1}, {0, -7, 0});
  EXPECT_TRUE(std::isinf(edge_on.amin) && std::isinf(edge_on.amax));
  // A vertex level with the light: its projection is unbounded.
  const CullBox beside = boxOf({-1, -5, -1}, {1, -5, -1}, {3, 0, 0});
  EXPECT_TRUE(std::isinf(beside.amin) && std::isinf(beside.amax));
}

TEST(LightCulling, BoxesAreMadeAgainOnlyWhenABatchOutgrowsThem) {
  std::vector<GrTriangle> tris;
  const glm::vec3 v[3] = {{-1, -5, -1}, {1, -5, -1}, {0, -5, 1}};
  tris.push_back(prepareTriangle(v, 0));
  const glm::vec3 light(0.0f);
  TowardsOrigin bounds;
  bounds.miss = 1e-5;
  bounds.ray_reach = 10.0;
  bounds.min_length = 1.0;
  std::array<bool, 6> down{};
  down[3] = true;
  LightCullCache cache;
  EXPECT_TRUE(cache.update(light, bounds, down, tris.data(), tris.size()));
  const std::vector<float> first = cache.planes();
  EXPECT_FALSE(cache.update(light, bounds, down, tris.data(), tris.size()));
  TowardsOrigin smaller = bounds;
  smaller.miss = 0.5e-5;
  EXPECT_FALSE(cache.update(light, smaller, down, tris.data(), tris.size()));
  TowardsOrigin larger = bounds;
  larger.miss = 3e-5;  // beyond the twice the first batch's the boxes were made for
  EXPECT_TRUE(cache.update(light, larger, down, tris.data(), tris.size()));
  const size_t stride = cache.stride();
  EXPECT_LT(cache.planes()[3 * 4 * stride], first[3 * 4 * stride]);  // amin grew outwards
  std::array<bool, 6> sideways = down;
  sideways[0] = true;  // a face without boxes yet
  EXPECT_TRUE(cache.update(light, larger, sideways, tris.data(), tris.size()));
  EXPECT_TRUE(
      cache.update(glm::vec3(0.0f, 1.0f, 0.0f), larger, sideways, tris.data(), tris.size()));
  EXPECT_FALSE(LightCullCache::usable(TowardsOrigin{INFINITY, 10.0, 1.0}));
  EXPECT_TRUE(LightCullCache::usable(bounds));
}

// The default scene's shadow rays from its camera hits, through the light bundles with light
// culling and with segment culling: both equal brute force, and light culling runs fewer tests.
TEST(LightCulling, ShadowRaysHitWhatBruteForceHits) {
  if (listDevices().empty()) GTEST_SKIP() << "no OpenCL device: install pocl-opencl-icd";
  auto runtime = std::make_unique<ClRuntime>("");
  const Scene scene = makeDefaultScene();
  const std::vector<GrTriangle> tris = prepareTriangles(scene);
  const Bounds bounds = sceneBounds(scene);
  BruteIntersector brute(*runtime, tris);
  std::vector<GrRay> camera;
  for (int j = 0; j < 120; ++j)
    for (int i = 0; i < 160; ++i)
      camera.push_back(cameraRay(scene.camera, 160, 120, i, j, 0.5f, 0.5f));
  std::vector<GrHit> camera_hits;
  brute.intersect(camera, HitMode::Closest, camera_hits, nullptr);
  const glm::vec3 light = scene.lights.at(0).position;
  std::vector<GrRay> rays;
  for (size_t i = 0; i < camera.size(); ++i) {
    if (camera_hits[i].prim < 0) continue;
    const GrRay& c = camera[i];
    const glm::vec3 p =
        glm::vec3(c.ox, c.oy, c.oz) + camera_hits[i].t * 0.9999f * glm::vec3(c.dx, c.dy, c.dz);
    const glm::vec3 to = light - p;
    const float distance = glm::length(to);
    const glm::vec3 d = to / distance;
    rays.push_back(GrRay{p.x, p.y, p.z, 1e-4f, d.x, d.y, d.z, distance});
  }
  ASSERT_GT(rays.size(), 10000u);
  std::vector<GrHit> want, got;
  brute.intersect(rays, HitMode::Closest, want, nullptr);
  const UniformGrid grid = buildUniformGrid(tris, bounds, GridSettings{});
  uint64_t tests_run[2] = {0, 0};
  KernelOptions packets;  // culling is the packet kernels' (PeLayout): on any device
  packets.pe_layout = PeLayout::Packets;
  for (bool light_culling : {true, false}) {
    GridRtIntersector gridrt(*runtime, grid, PeInterrupt::Off, packets);
    gridrt.forceLightBundles();
    gridrt.allowLightCulling(light_culling);
    gridrt.intersectTowardsPoint(light, rays, HitMode::Closest, got);
    const std::string label = light_culling ? "light culling" : "segment culling";
    EXPECT_EQ(test::hitMismatches(want, got, label), 0u);
    tests_run[light_culling] = gridrt.counters().tests_run;
  }
  // Light culling is used (on this scene it skips more triangles than segment culling).
  EXPECT_LT(tests_run[1], tests_run[0]);
}

}  // namespace
}  // namespace gridrt
