// Segment culling (host/gridrt/culling/segment_culling.h): wherever the ray/triangle test reports a
// hit, the ray's point at that t must lie within the margin of the triangle, including the hits
// that the test's rounding lets through just outside it; grazing rays and slivers are never culled;
// and Whitted frames rendered through the culling kernels equal brute force's.
#include "segment_culling.h"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <random>

#include "brute_intersector.h"
#include "cl_runtime.h"
#include "default_scene.h"
#include "gridrt_intersector.h"
#include "prepared_triangles.h"
#include "renderer.h"
#include "test_support.h"
#include "uniform_grid.h"

namespace gridrt {
namespace {

// Distance from p to the triangle (a, b, c), in double (closest point by regions).
double distanceToTriangle(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& b,
                          const glm::dvec3& c) {
  const glm::dvec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = glm::dot(ab, ap), d2 = glm::dot(ac, ap);
  if (d1 <= 0 && d2 <= 0) return glm::length(p - a);
  const glm::dvec3 bp = p - b;
  const double d3 = glm::dot(ab, bp), d4 = glm::dot(ac, bp);
  if (d3 >= 0 && d4 <= d3) return glm::length(p - b);
  const glm::dvec3 cp = p - c;
  const double d5 = glm::dot(ab, cp), d6 = glm::dot(ac, cp);
  if (d6 >= 0 && d5 <= d6) return glm::length(p - c);
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return glm::length(p - (a + ab * (d1 / (d1 - d3))));
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return glm::length(p - (a + ac * (d2 / (d2 - d6))));
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0)
    return glm::length(p - (b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)))));
  const double denom = 1.0 / (va + vb + vc);
  return glm::length(p - (a + ab * (vb * denom) + ac * (vc * denom)));
}

struct Violations {
  size_t hits = 0;     // hits the test reported (t > 0) where the margin is finite
  size_t outside = 0;  // ... whose point lies further from the triangle than the margin
};

// Random triangles (a third of them slivers), rays from random origins (a third of them
// close to the triangle's plane: steep incidence) aimed at the vertices and edges with a
// tiny random miss, where the test's rounding decides.
Violations countViolations(bool watertight, double error_factor) {
  std::mt19937 rng(4321);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  Violations result;
  for (int trial = 0; trial < 600; ++trial) {
    const glm::vec3 centre(unit(rng) * 50.0f, unit(rng) * 50.0f, unit(rng) * 50.0f);
    glm::vec3 v[3];
    for (glm::vec3& x : v) x = centre + glm::vec3(unit(rng), unit(rng), unit(rng));
    if (trial % 3 == 0) v[2] = v[0] + (v[1] - v[0]) * 0.5f + (v[2] - v[0]) * 0.01f;
    glm::vec3 origin = centre + glm::vec3(unit(rng), unit(rng), unit(rng)) * 20.0f;
    if (trial % 3 == 1) {  // pull the origin towards the triangle's plane
      const glm::vec3 n = glm::normalize(glm::cross(v[1] - v[0], v[2] - v[0]));
      origin -= n * (glm::dot(origin - v[0], n) * 0.99f);
    }
    const GrTriangle tri = prepareTriangle(v, 0, KernelOptions{watertight});
    std::vector<float> planes;
    computeSegmentCullPlanes({tri}, planes);
    glm::dvec3 seen[3];  // the triangle as the test sees it
    triangleVertices(tri, seen);
    for (int ray = 0; ray < 2000; ++ray) {
      const float scale = std::ldexp(1.0f, -10 - int(rng() % 14));
      const float along = (ray / 3) % 2 ? 0.0f : std::abs(unit(rng));  // vertex or edge
      const glm::vec3 aim = v[ray % 3] + along * (v[(ray + 1) % 3] - v[ray % 3]);
      const glm::vec3 miss = glm::vec3(unit(rng), unit(rng), unit(rng)) * scale;
      const glm::vec3 d = glm::normalize(aim + miss - origin);
      float t, u, w;
      const int hit = test::intersectScalar(tri, origin, d, &t, &u, &w);
      if (!hit || !(t > 0.0f)) continue;
      const GrRay r{origin.x, origin.y, origin.z, 0.0f, d.x, d.y, d.z, INFINITY};
      const double margin = segmentCullMargin(planes, 0, r, t, error_factor);
      if (std::isinf(margin)) continue;
      ++result.hits;
      const glm::dvec3 point = glm::dvec3(origin) + double(t) * glm::dvec3(d);
      result.outside += distanceToTriangle(point, seen[0], seen[1], seen[2]) > margin;
    }
  }
  return result;
}

TEST(SegmentCulling, MarginCoversTheTestsRounding) {
  for (bool watertight : {false, true}) {
    const char* name = watertight ? "watertight" : "Moeller-Trumbore";
    const Violations with = countViolations(watertight, kSegmentCullErrorFactor);
    EXPECT_GT(with.hits, 200000u) << name;
    EXPECT_EQ(with.outside, 0u) << name;
    // Without the margin, hits the float test reports lie outside the exact triangle.
    const Violations without = countViolations(watertight, 0.0);
    EXPECT_GT(without.outside, 0u) << name;
  }
}

// The planes of many triangles, written in slices on all cores, equal each triangle's own
// planes computed alone, and the padding after each plane is zero.
TEST(SegmentCulling, PlanesOfManyTrianglesEqualEachTrianglesOwn) {
  std::mt19937 rng(99);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  std::vector<GrTriangle> tris;
  for (int k = 0; k < 5003; ++k) {
    glm::vec3 v[3];
    for (glm::vec3& x : v) x = glm::vec3(unit(rng), unit(rng), unit(rng)) * 10.0f;
    tris.push_back(prepareTriangle(v, k, KernelOptions{k % 2 == 0}));
  }
  std::vector<float> planes;
  computeSegmentCullPlanes(tris, planes);
  const size_t stride = tris.size() + kSegmentCullPlanePadding;
  ASSERT_EQ(planes.size(), GR_SEG_PLANES * stride);
  for (size_t i = 0; i < tris.size(); ++i) {
    std::vector<float> own;
    computeSegmentCullPlanes({tris[i]}, own);
    for (int p = 0; p < GR_SEG_PLANES; ++p)
      ASSERT_EQ(planes[p * stride + i], own[p * (1 + kSegmentCullPlanePadding)])
          << "triangle " << i << " plane " << p;
  }
  for (int p = 0; p < GR_SEG_PLANES; ++p)
    for (size_t i = tris.size(); i < stride; ++i) ASSERT_EQ(planes[p * stride + i], 0.0f);
}

TEST(SegmentCulling, GrazingRaysAndSliversAreNeverCulled) {
  auto planesOf = [](glm::vec3 a, glm::vec3 b, glm::vec3 c) {
    const glm::vec3 v[3] = {a, b, c};
    std::vector<float> planes;
    computeSegmentCullPlanes({prepareTriangle(v, 0)}, planes);
    return planes;
  };
  const auto square = planesOf({0, 0, 0}, {1, 0, 0}, {0, 1, 0});
  const GrRay head_on{0.2f, 0.2f, 5.0f, 0.0f, 0.0f, 0.0f, -1.0f, INFINITY};
  const double margin = segmentCullMargin(square, 0, head_on, 5.0f);
  EXPECT_GT(margin, 0.0);
  EXPECT_LT(margin, 1e-3);
  // In the plane, and 1/2000 off it (K = 2000 > kSegmentCullMaxConditioning).
  const GrRay along{-1.0f, 0.2f, 0.0f, 0.0f, 1.0f, 0.0f, 0.0f, INFINITY};
  EXPECT_TRUE(std::isinf(segmentCullMargin(square, 0, along, 1.0f)));
  const glm::vec3 shallow = glm::normalize(glm::vec3(1.0f, 0.0f, -5e-4f));
  const GrRay grazing{-1.0f, 0.2f, 0.001f, 0.0f, shallow.x, shallow.y, shallow.z, INFINITY};
  EXPECT_TRUE(std::isinf(segmentCullMargin(square, 0, grazing, 1.0f)));
  // A sliver (angle 1e-4 at v0) is ill-conditioned for every ray; a degenerate one too.
  const auto sliver = planesOf({0, 0, 0}, {1, 0, 0}, {1, 1e-4f, 0});
  EXPECT_TRUE(std::isinf(segmentCullMargin(sliver, 0, head_on, 5.0f)));
  const auto degenerate = planesOf({0, 0, 0}, {1, 0, 0}, {2, 0, 0});
  EXPECT_TRUE(std::isinf(segmentCullMargin(degenerate, 0, head_on, 5.0f)));
}

class SegmentCullingKernels : public ::testing::Test {
 protected:
  void SetUp() override {
    if (listDevices().empty()) GTEST_SKIP() << "no OpenCL device: install pocl-opencl-icd";
    runtime_ = std::make_unique<ClRuntime>("");
  }
  std::unique_ptr<ClRuntime> runtime_;
};

// Whitted frames of the default scene (mirror and glass: reflection, refraction and
// shadow rays with their own origins, culled in the list and light-bundle kernels) equal
// brute force's pixel for pixel, for both ray/triangle tests and two grid densities.
TEST_F(SegmentCullingKernels, WhittedFramesOfTheDefaultSceneEqualBrute) {
  const Scene scene = makeDefaultScene();
  const Camera camera = scene.camera;
  RenderSettings settings;
  settings.width = 160;
  settings.height = 120;
  settings.max_depth = 5;
  auto render = [&](Intersector& intersector) {
    Renderer renderer(scene, camera, intersector, settings);
    Frame frame;
    renderer.render(frame);
    return frame.film.rgb;
  };
  for (bool watertight : {false, true}) {
    KernelOptions options;
    options.watertight = watertight;
    const auto tris = prepareTriangles(scene, options);
    BruteIntersector brute(*runtime_, tris, options);
    const std::vector<float> want = render(brute);
    for (float density : {kDefaultGridDensity, 4.0f}) {
      GridSettings grid_settings;
      grid_settings.density = density;
      const UniformGrid grid = buildUniformGrid(tris, sceneBounds(scene), grid_settings);
      GridRtIntersector gridrt(*runtime_, grid, PeInterrupt::Off, options);
      const std::vector<float> got = render(gridrt);
      size_t differ = 0;
      for (size_t k = 0; k < want.size(); ++k) differ += want[k] != got[k];
      EXPECT_EQ(differ, 0u) << (watertight ? "watertight" : "mt") << " density " << density;
      EXPECT_GT(gridrt.counters().rays, 2 * size_t(settings.width * settings.height));
    }
  }
}

}  // namespace
}  // namespace gridrt
