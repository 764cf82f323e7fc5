// Light bundles' cells (host/gridrt/bundles/light_bundles.h): the cells a voxel's projected outline
// covers must hold every ray whose face coordinate lies in the outline up to rounding; a PE
// behind every ray's origin (further from the light) receives none of them.
#include "light_bundles.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <set>

#include "prepared_triangles.h"
#include "uniform_grid.h"

namespace gridrt {
namespace {

// A face of 64 x 64 cells over [-1, 1]^2: cell boundaries at -1 + k / 32, exact in float.
FaceWindow gridOf64() {
  FaceWindow w;
  w.umin = w.vmin = -1.0f;
  w.umax = w.vmax = 1.0f;
  w.count = 64 * 64 * 8;
  w.layout(0, 0);
  return w;
}

// The column a ray with face coordinates (u, 0) falls in.
int columnOf(const FaceWindow& w, float u) { return int(w.cellOf(u, 0.0f) % size_t(w.res)); }

// `ulps` float steps from x towards `to`.
float stepped(float x, float to, int ulps) {
  for (int k = 0; k < ulps; ++k) x = std::nextafter(x, to);
  return x;
}

TEST(LightBundles, FaceWindowOfTheTestHas64Columns) {
  const FaceWindow w = gridOf64();
  ASSERT_EQ(w.res, 64);
  EXPECT_EQ(columnOf(w, -0.5f), 16);
  EXPECT_EQ(columnOf(w, std::nextafter(-0.5f, -1.0f)), 15);
}

// A box corner's face coordinate and a ray's are each a few roundings from exact
// (kLightFaceMargin): a ray 4 ulps outside an outline that ends on a cell boundary lies
// in the next cell, which the outline's range must include. Without the margin 48 of the
// 64 cases below fail (in the other 16, u - u0 rounds the outline's end onto the
// boundary). Boundaries with |u| >= 0.5 only: nearer 0 the ulps of u are below those of
// u - u0 and vanish in the cell arithmetic.
TEST(LightBundles, CellRangeHoldsCoordinatesAFewUlpsOutsideTheOutline) {
  const FaceWindow w = gridOf64();
  int failures = 0, checked = 0;
  for (int k = 1; k < 64; ++k) {
    const float boundary = -1.0f + float(k) / 32.0f;
    if (std::fabs(boundary) < 0.5f) continue;
    checked += 2;
    int c0, c1;
    // The outline starts on the boundary; the ray lies just below it.
    w.cellRange(boundary, 0.99f, w.u0, w.su, c0, c1);
    const int below = columnOf(w, stepped(boundary, -2.0f, 4));
    ASSERT_EQ(below, k - 1) << "boundary " << boundary;
    failures += !(c0 <= below && below < c1);
    // The outline ends one ulp below the boundary; the ray lies 4 ulps above that end.
    const float end = std::nextafter(boundary, -2.0f);
    w.cellRange(-0.99f, end, w.u0, w.su, c0, c1);
    const int above = columnOf(w, stepped(end, 2.0f, 4));
    ASSERT_EQ(above, k) << "boundary " << boundary;
    failures += !(c0 <= above && above < c1);
  }
  EXPECT_EQ(checked, 64);
  EXPECT_EQ(failures, 0);
}

// The margin is relative: far outside the window (a corner projected near the light's
// plane) it still covers a few ulps, and it never reaches a whole cell of this face.
TEST(LightBundles, CellRangeMarginStaysBelowACell) {
  const FaceWindow w = gridOf64();
  int c0, c1;
  w.cellRange(-0.5f, -0.5f + 1.0f / 64.0f, w.u0, w.su, c0, c1);  // half a cell wide
  EXPECT_EQ(c0, 15);  // the margin reaches just below the boundary at -0.5
  EXPECT_EQ(c1, 17);
  w.cellRange(-0.25f + 1e-3f, -0.25f + 2e-3f, w.u0, w.su, c0, c1);  // inside one cell
  EXPECT_EQ(c0, 24);
  EXPECT_EQ(c1, 25);
  w.cellRange(5.0f, 1e30f, w.u0, w.su, c0, c1);  // right of the window: nothing
  EXPECT_EQ(c0, 64);
  EXPECT_EQ(c1, 64);
}

// The slack of light bundles must bound how far each ray's exact end o + tmax * d lies
// from the light. Rays built so that their float end is the light itself (o = -(tmax * d)
// in float, the light at the origin) still miss it by the rounding of tmax * d: their
// measured distance is 0, and only the rounding term (kLightEndRoundingEpsilons) covers
// them. Without it every one of these rays falls short.
TEST(LightBundles, MissOfLightBoundsTheExactEndsDistance) {
  const glm::vec3 light(0.0f);
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f), length(1.0f, 1000.0f);
  int float_end_on_light = 0, short_of_exact = 0;
  for (int k = 0; k < 10000; ++k) {
    const glm::vec3 d = glm::normalize(glm::vec3(unit(rng), unit(rng), unit(rng)));
    const float tmax = length(rng);
    const glm::vec3 step = tmax * d;
    const GrRay ray{-step.x, -step.y, -step.z, 0.0f, d.x, d.y, d.z, tmax};
    const glm::vec3 float_end = glm::vec3(ray.ox, ray.oy, ray.oz) + ray.tmax * d;
    float_end_on_light += float_end == light;
    // The exact end, in double (a float product is exact there; the sum rounds far below).
    const double ex = double(ray.ox) + double(tmax) * double(d.x);
    const double ey = double(ray.oy) + double(tmax) * double(d.y);
    const double ez = double(ray.oz) + double(tmax) * double(d.z);
    const double exact_miss = std::sqrt(ex * ex + ey * ey + ez * ez);
    short_of_exact += double(missOfLight(ray, light)) < exact_miss;
  }
  EXPECT_EQ(float_end_on_light, 10000);
  EXPECT_EQ(short_of_exact, 0);
}

// The batch's bounds, taken from squared lengths with one root at the end, must still
// hold each ray's own: bounds.miss at least every ray's missOfLight (rays whose float end
// is the light: only the rounding term keeps it above 0) and bounds.min_length exactly the
// shortest |d|.
TEST(LightBundles, BatchBoundsHoldEveryRaysOwn) {
  const glm::vec3 corners[3] = {{1.0f, 0.0f, 0.0f}, {0.0f, 1.0f, 0.0f}, {0.0f, 0.0f, 1.0f}};
  const std::vector<GrTriangle> tris = {prepareTriangle(corners, 0)};
  Bounds box;
  box.grow(glm::vec3(-2.0f));
  box.grow(glm::vec3(2.0f));
  const UniformGrid grid = buildUniformGrid(tris, box, GridSettings{});
  const glm::vec3 light(0.0f);
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f), length(1.0f, 1000.0f);
  std::vector<GrRay> rays;
  float largest_miss = 0.0f, shortest = INFINITY;
  for (int k = 0; k < 5000; ++k) {
    const glm::vec3 d = length(rng) * glm::vec3(unit(rng), unit(rng), unit(rng));
    const float tmax = 1.0f + std::fabs(unit(rng));
    const glm::vec3 step = tmax * d;
    rays.push_back(GrRay{-step.x, -step.y, -step.z, 0.0f, d.x, d.y, d.z, tmax});
    largest_miss = std::max(largest_miss, missOfLight(rays.back(), light));
    shortest = std::min(shortest, glm::length(d));
  }
  ASSERT_GT(largest_miss, 0.0f);
  RayBundles bundles;
  LightBundleScratch scratch;
  const LightRayBounds bounds =
      bundleLightRays(grid, light, rays.data(), rays.size(), bundles, scratch);
  EXPECT_GE(bounds.miss, largest_miss);
  EXPECT_EQ(bounds.min_length, shortest);
}

// Two layers of triangles under a light: shadow rays start on the upper layer's plane,
// so the lower layer's PEs lie behind every origin (seen from the light) and receive none
// of them, though their outlines on the light's cube cover the same cells; the upper
// layer's PEs, whose boxes reach up to the origins' plane, receive them all. Without the
// depth test the lower PEs receive as many rays as the upper ones.
TEST(LightBundles, PesBehindEveryOriginReceiveNoRays) {
  std::vector<GrTriangle> tris;
  for (float y : {1.0f, 3.0f})
    for (int x = 0; x < 4; ++x)
      for (int z = 0; z < 4; ++z) {
        const glm::vec3 v[3] = {
            {x + 0.1f, y, z + 0.1f}, {x + 0.9f, y, z + 0.1f}, {x + 0.5f, y, z + 0.9f}};
        tris.push_back(prepareTriangle(v, int(tris.size())));
      }
  GridSettings settings;
  settings.automatic = false;
  settings.dims = {4, 4, 4};
  Bounds box;
  box.grow(glm::vec3(0.0f));
  box.grow(glm::vec3(4.0f));
  const UniformGrid grid = buildUniformGrid(tris, box, settings);
  const glm::vec3 light(2.0f, 10.0f, 2.0f);
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> unit(0.1f, 3.9f);
  std::vector<GrRay> rays;
  for (int k = 0; k < 4000; ++k) {
    const glm::vec3 o(unit(rng), 3.0f, unit(rng)), to = light - o;
    const glm::vec3 d = glm::normalize(to);
    rays.push_back(GrRay{o.x, o.y, o.z, 1e-4f, d.x, d.y, d.z, glm::length(to)});
  }
  RayBundles bundles;
  LightBundleScratch scratch;
  bundleLightRays(grid, light, rays.data(), rays.size(), bundles, scratch);
  size_t lower = 0, upper = 0;
  for (const GrBundleTask& task : bundles.tasks) {
    glm::vec3 lo, hi;
    grid.hullOfPe(task.pe, lo, hi);
    (hi.y < 2.0f ? lower : upper) += size_t(task.ray_count);
  }
  EXPECT_EQ(lower, 0u);
  EXPECT_GE(upper, rays.size());
}

}  // namespace
}  // namespace gridrt
