// Phase 2's tie rule: a ray keeps the smallest (t, prim) over its PEs' hits, so on an exact
// tie in t between different triangles in different PEs the lower triangle index wins,
// whichever PE comes first along the ray (as brute force decides).
#include <gtest/gtest.h>

#include <limits>
#include <memory>

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

// The PEs whose triangle lists hold triangle `prim`.
std::vector<int> pesHolding(const UniformGrid& grid, int prim) {
  std::vector<int> pes;
  for (int pe = 0; pe < grid.peCount(); ++pe)
    for (int k = grid.pe_tri_begin[pe]; k < grid.pe_tri_begin[pe + 1]; ++k)
      if (grid.pe_triangles[k].prim == prim) pes.push_back(pe);
  return pes;
}

// With both PE layouts and both batch transfers.
class PhaseTwo : public ::testing::TestWithParam<test::KernelChoice> {};

INSTANTIATE_TEST_SUITE_P(Kernels, PhaseTwo, test::kernelChoices(), test::kernelChoiceName);

TEST_P(PhaseTwo, ExactTieBetweenTrianglesInDifferentPesGoesToTheLowerIndex) {
  if (listDevices().empty()) GTEST_SKIP() << "no OpenCL device: install pocl-opencl-icd";
  ClRuntime runtime("");
  // Two triangles 1e-3 apart on either side of the plane z = 0, the boundary of a 1x1x2
  // grid over z in [-1, 1] (pinned by two small triangles off the rays), each clear of the
  // other's voxel by more than the grid's margin (8e-5 here). Seen from z = -6e4, where the
  // floats are 3.9e-3 apart, t = 6e4 +- 5e-4 rounds to the same float: an exact tie
  // between a triangle met in the first PE along the rays (index 1, below the boundary, in
  // PE 0, which tends to run first) and one met in the second (index 0, above it).
  const float e = 5e-4f;
  std::vector<GrTriangle> tris = {
      tri({-1, -1, e}, {1, -1, e}, {-1, 1, e}, 0),     // above z = 0: the second PE
      tri({-1, -1, -e}, {1, -1, -e}, {-1, 1, -e}, 1),  // below: the first PE along the rays
      tri({2, 2, 1}, {2.1f, 2, 1}, {2, 2.1f, 1}, 2),
      tri({-2, -2, -1}, {-2.1f, -2, -1}, {-2, -2.1f, -1}, 3)};
  Bounds b;
  for (glm::vec3 p : {glm::vec3(-2.1f, -2.1f, -1), glm::vec3(2.1f, 2.1f, 1)}) b.grow(p);
  GridSettings settings;
  settings.automatic = false;
  settings.dims = {1, 1, 2};
  const UniformGrid grid = buildUniformGrid(tris, b, settings);
  ASSERT_EQ(grid.peCount(), 2);
  const std::vector<int> pes0 = pesHolding(grid, 0), pes1 = pesHolding(grid, 1);
  ASSERT_EQ(pes0.size(), 1u);
  ASSERT_EQ(pes1.size(), 1u);
  ASSERT_NE(pes0[0], pes1[0]) << "the two triangles must lie in different PEs";

  // Straight up through the lower-left half of the squares (both triangles there).
  std::vector<GrRay> rays;
  for (int j = 0; j < 16; ++j)
    for (int i = 0; i < 16; ++i) {
      const float x = -0.9f + 0.05f * i, y = -0.9f + 0.05f * j;
      rays.push_back(GrRay{x, y, -6e4f, 0.0f, 0.0f, 0.0f, 1.0f, kInf});
    }
  // Which rays really tie: each triangle's own t, by the scalar test.
  std::vector<bool> tie;
  size_t ties = 0;
  for (const GrRay& r : rays) {
    float t0, t1, u, v;
    const glm::vec3 o(r.ox, r.oy, r.oz), d(r.dx, r.dy, r.dz);
    ASSERT_TRUE(test::intersectScalar(tris[0], o, d, &t0, &u, &v));
    ASSERT_TRUE(test::intersectScalar(tris[1], o, d, &t1, &u, &v));
    tie.push_back(t0 == t1);
    ties += t0 == t1;
  }
  ASSERT_GT(ties, rays.size() / 2) << "the set-up no longer makes exact ties";

  BruteIntersector brute(runtime, tris);
  std::vector<GrHit> want, got;
  brute.intersect(rays, HitMode::Closest, want, nullptr);
  for (PeInterrupt interrupt : {PeInterrupt::Off, PeInterrupt::AllRays}) {
    GridRtIntersector gridrt(runtime, grid, interrupt, GetParam().options());
    RayDiagnostics diagnostics;
    gridrt.intersect(rays, HitMode::Closest, got, &diagnostics);
    EXPECT_EQ(test::hitMismatches(want, got, gridrt.name()), 0u);
    size_t lower = 0;
    for (size_t r = 0; r < rays.size(); ++r) lower += tie[r] && got[r].prim == 0;
    EXPECT_EQ(lower, ties) << gridrt.name() << ": the lower index must win every tie";
  }
}

}  // namespace
}  // namespace gridrt
