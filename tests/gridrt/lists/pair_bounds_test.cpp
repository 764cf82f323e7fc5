// The bounds a list pair carries (gr_pair_bounds, gridrt_types.h): a hit must lie in the
// ray's open interval (tmin, tmax) and in the PE's closed [t_enter, t_exit]. A pair holds
// the two as one interval whose ends say whether they are the ray's (open) or the voxel's
// (closed); these tests put hits exactly on each kind of end.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "brute_intersector.h"
#include "cl_runtime.h"
#include "gridrt_intersector.h"
#include "kernel_choices.h"
#include "prepared_triangles.h"
#include "test_support.h"
#include "test_triangles.h"
#include "uniform_grid.h"

namespace gridrt {
namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();

using test::tri;

// A grid of nx x ny x nz voxels over [-1, 1]^3.
UniformGrid gridOverUnitCube(const std::vector<GrTriangle>& tris, int nx, int ny, int nz) {
  Bounds b;
  for (glm::vec3 p : {glm::vec3(-1, -1, -1), glm::vec3(1, 1, 1)}) b.grow(p);
  GridSettings settings;
  settings.automatic = false;
  settings.dims = {nx, ny, nz};
  return buildUniformGrid(tris, b, settings);
}

TEST(PairBounds, OneIntervalTestsLikeTheFourBounds) {
  float lo = 0.0f, hi = 0.0f;
  // The ray's ends inside the voxel's interval: open.
  int bits = gr_pair_bounds(1.0f, 2.0f, 0.5f, 3.0f, &lo, &hi);
  EXPECT_EQ(lo, 1.0f);
  EXPECT_EQ(hi, 2.0f);
  EXPECT_EQ(bits, GR_PAIR_LO_OPEN | GR_PAIR_HI_OPEN);
  // The voxel's inside the ray's: closed.
  bits = gr_pair_bounds(0.5f, 3.0f, 1.0f, 2.0f, &lo, &hi);
  EXPECT_EQ(lo, 1.0f);
  EXPECT_EQ(hi, 2.0f);
  EXPECT_EQ(bits, 0);
  // Equal ends: t > tmin and t >= t_enter is t > tmin (open); likewise above.
  bits = gr_pair_bounds(1.0f, 2.0f, 1.0f, 2.0f, &lo, &hi);
  EXPECT_EQ(bits, GR_PAIR_LO_OPEN | GR_PAIR_HI_OPEN);
  // A NaN end lets nothing through, as the four comparisons did.
  bits = gr_pair_bounds(NAN, 2.0f, 1.0f, 3.0f, &lo, &hi);
  EXPECT_TRUE(std::isnan(lo));
  bits = gr_pair_bounds(0.0f, 2.0f, 1.0f, NAN, &lo, &hi);
  EXPECT_TRUE(std::isnan(hi));
  bits = gr_pair_bounds(0.0f, NAN, 1.0f, 3.0f, &lo, &hi);
  EXPECT_TRUE(std::isnan(hi));
}

// With both PE layouts and both batch transfers.
class PairBounds : public ::testing::TestWithParam<test::KernelChoice> {};

INSTANTIATE_TEST_SUITE_P(Kernels, PairBounds, test::kernelChoices(), test::kernelChoiceName);

TEST_P(PairBounds, HitsOnTheRaysEndsAreOutsideItAndJustInsideThemAreHits) {
  if (listDevices().empty()) GTEST_SKIP() << "no OpenCL device: install pocl-opencl-icd";
  ClRuntime runtime("");
  // A square at z = 0.3 in the upper voxel of a 1x1x2 grid over z in [-1, 1], and rays
  // straight up from inside the lower one: each ray's list holds both voxels, and the
  // square's hit lies well inside the upper one.
  const std::vector<GrTriangle> tris = {tri({-1, -1, 0.3f}, {1, -1, 0.3f}, {-1, 1, 0.3f}, 0),
                                        tri({1, 1, 0.3f}, {-1, 1, 0.3f}, {1, -1, 0.3f}, 1),
                                        tri({-1, -1, -1}, {-0.9f, -1, -1}, {-1, -0.9f, -1}, 2)};
  const UniformGrid grid = gridOverUnitCube(tris, 1, 1, 2);

  // For each start, four rays: tmax on the hit (no hit), tmax just past it (a hit), tmin
  // on it (no hit) and tmin just before it (a hit).
  std::vector<GrRay> rays;
  std::vector<int> want_prim;
  for (int j = 0; j < 8; ++j)
    for (int i = 0; i < 8; ++i) {
      const glm::vec3 o(-0.8f + 0.21f * i, -0.8f + 0.19f * j, -0.37f - 0.01f * float(i + j));
      const glm::vec3 d(0.0f, 0.0f, 1.0f);
      float t = kInf, u, v;
      int prim = -1;
      for (const GrTriangle& candidate : tris) {
        float tc;
        if (test::intersectScalar(candidate, o, d, &tc, &u, &v) && tc > 0.0f && tc < t) {
          t = tc;
          prim = candidate.prim;
        }
      }
      ASSERT_GE(prim, 0) << "every ray meets the square";
      auto ray = [&](float tmin, float tmax) {
        rays.push_back(GrRay{o.x, o.y, o.z, tmin, d.x, d.y, d.z, tmax});
      };
      ray(0.0f, t);
      want_prim.push_back(-1);
      ray(0.0f, std::nextafter(t, kInf));
      want_prim.push_back(prim);
      ray(t, kInf);
      want_prim.push_back(-1);
      ray(std::nextafter(t, 0.0f), kInf);
      want_prim.push_back(prim);
    }

  BruteIntersector brute(runtime, tris);
  std::vector<GrHit> want, got;
  brute.intersect(rays, HitMode::Closest, want, nullptr);
  for (PeInterrupt interrupt : {PeInterrupt::Off, PeInterrupt::AllRays}) {
    GridRtIntersector gridrt(runtime, grid, interrupt, GetParam().options());
    gridrt.intersect(rays, HitMode::Closest, got, nullptr);
    ASSERT_EQ(got.size(), rays.size());
    EXPECT_EQ(test::hitMismatches(want, got, gridrt.name()), 0u);
    size_t wrong = 0;
    for (size_t r = 0; r < rays.size(); ++r) wrong += got[r].prim != want_prim[r];
    EXPECT_EQ(wrong, 0u) << gridrt.name() << ": a hit on a ray's end is outside the ray";
  }
}

// Any-hit rays stop testing once every lane has a hit: one on the ray's tmax must not count,
// or a ray ending exactly on a far triangle would stop before a nearer one and miss.
TEST_P(PairBounds, AnyHitRaysEndingOnAFarHitStillFindTheNearOne) {
  if (listDevices().empty()) GTEST_SKIP() << "no OpenCL device: install pocl-opencl-icd";
  ClRuntime runtime("");
  auto square = [&](float z, int prim) {
    return std::vector<GrTriangle>{tri({-1, -1, z}, {1, -1, z}, {-1, 1, z}, prim),
                                   tri({1, 1, z}, {-1, 1, z}, {1, -1, z}, prim + 1)};
  };
  // Both squares in one PE, the far one (z = 0.6) tested first in one scene, last in the
  // other; rays up from z = -0.5 end exactly on the far one.
  for (bool far_first : {true, false}) {
    std::vector<GrTriangle> tris = far_first ? square(0.6f, 0) : square(0.2f, 0);
    for (const GrTriangle& t : far_first ? square(0.2f, 2) : square(0.6f, 2)) tris.push_back(t);
    const UniformGrid grid = gridOverUnitCube(tris, 1, 1, 1);
    std::vector<GrRay> rays;
    for (int j = 0; j < 8; ++j)
      for (int i = 0; i < 8; ++i) {
        const glm::vec3 o(-0.8f + 0.21f * i, -0.8f + 0.19f * j, -0.5f);
        const glm::vec3 d(0.0f, 0.0f, 1.0f);
        float far_t = -1.0f, u, v;
        for (const GrTriangle& candidate : tris) {
          float tc;
          if (test::intersectScalar(candidate, o, d, &tc, &u, &v) && tc > far_t) far_t = tc;
        }
        ASSERT_GT(far_t, 1.0f) << "every ray meets the far square";
        rays.push_back(GrRay{o.x, o.y, o.z, 0.0f, d.x, d.y, d.z, far_t});
      }
    std::vector<GrHit> got;
    GridRtIntersector gridrt(runtime, grid, PeInterrupt::Off, GetParam().options());
    gridrt.intersect(rays, HitMode::AnyHit, got, nullptr);
    ASSERT_EQ(got.size(), rays.size());
    size_t missed = 0;
    for (const GrHit& hit : got) missed += hit.prim < 0;
    EXPECT_EQ(missed, 0u) << "far square first: " << far_first;
  }
}

}  // namespace
}  // namespace gridrt
