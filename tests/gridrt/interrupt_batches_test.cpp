// The emulated interrupt (PeInterrupt::AllRays, --pe-interrupt) on batch after batch of one
// intersector: each batch starts with no ray marked as hit, so a ray never skips a PE
// because of a hit of the ray that held its slot in the batch before. Every batch is
// checked against brute force: list batches (closest and any hit) and light bundles
// towards several points in turn.
#include <gtest/gtest.h>

#include <glm/glm.hpp>
#include <limits>
#include <random>

#include "bounds.h"
#include "brute_intersector.h"
#include "default_scene_fixture.h"
#include "gridrt_intersector.h"
#include "prepared_triangles.h"
#include "test_support.h"
#include "uniform_grid.h"

namespace gridrt {
namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();

class InterruptBatches : public test::DefaultSceneTest {
 protected:
  // Rays from points inside the box in random directions.
  std::vector<GrRay> randomRays(unsigned seed, size_t n) const {
    std::mt19937 rng(seed);
    std::normal_distribution<float> g;
    std::vector<GrRay> rays;
    for (size_t k = 0; k < n; ++k) {
      const glm::vec3 o = inside(rng), d = glm::normalize(glm::vec3(g(rng), g(rng), g(rng)));
      rays.push_back(GrRay{o.x, o.y, o.z, 0.0f, d.x, d.y, d.z, kInf});
    }
    return rays;
  }
  // Shadow rays from points inside the box to `light`, ending there.
  std::vector<GrRay> raysTowards(const glm::vec3& light, unsigned seed, size_t n) const {
    std::mt19937 rng(seed);
    std::vector<GrRay> rays;
    for (size_t k = 0; k < n; ++k) {
      const glm::vec3 o = inside(rng), to = light - o;
      const float distance = glm::length(to);
      const glm::vec3 d = to / distance;
      rays.push_back(GrRay{o.x, o.y, o.z, 0.0f, d.x, d.y, d.z, distance});
    }
    return rays;
  }
  // Rays whose hit or miss differs.
  static size_t hitOrMissDiffers(const std::vector<GrHit>& want, const std::vector<GrHit>& got) {
    size_t differ = 0;
    for (size_t r = 0; r < want.size(); ++r) differ += (want[r].prim >= 0) != (got[r].prim >= 0);
    return differ;
  }
};

TEST_F(InterruptBatches, ListBatchesOneAfterAnotherMatchBruteForce) {
  const UniformGrid grid = buildUniformGrid(triangles_, sceneBounds(scene_), GridSettings{});
  // The packet kernels, on any device: how many pairs are skipped depends on which PEs run
  // before which, and a GPU running every ray of the lane kernels at once may skip none
  // (their hits with the interrupt: the conformance suite).
  KernelOptions packets;
  packets.pe_layout = PeLayout::Packets;
  GridRtIntersector gridrt(*runtime_, grid, PeInterrupt::AllRays, packets);
  BruteIntersector brute(*runtime_, triangles_);
  std::vector<GrHit> want, got;
  for (unsigned batch = 0; batch < 4; ++batch) {
    const std::vector<GrRay> rays = randomRays(100 + batch, 4096);
    const std::string label = "batch " + std::to_string(batch);
    brute.intersect(rays, HitMode::Closest, want, nullptr);
    gridrt.intersect(rays, HitMode::Closest, got, nullptr);
    EXPECT_EQ(test::hitMismatches(want, got, label + " closest"), 0u);
    brute.intersect(rays, HitMode::AnyHit, want, nullptr);
    gridrt.intersect(rays, HitMode::AnyHit, got, nullptr);
    EXPECT_EQ(hitOrMissDiffers(want, got), 0u) << label << " any hit";
  }
  EXPECT_GT(gridrt.counters().skipped_pairs, 0u) << "the interrupt was not exercised";
}

TEST_F(InterruptBatches, LightBundlesTowardsOnePointAfterAnotherMatchBruteForce) {
  const UniformGrid grid = buildUniformGrid(triangles_, sceneBounds(scene_), GridSettings{});
  GridRtIntersector gridrt(*runtime_, grid, PeInterrupt::AllRays);
  gridrt.forceLightBundles();
  BruteIntersector brute(*runtime_, triangles_);
  std::mt19937 rng(7);
  std::vector<GrHit> want, got;
  for (unsigned batch = 0; batch < 6; ++batch) {
    const glm::vec3 light = inside(rng);
    const std::vector<GrRay> rays = raysTowards(light, 200 + batch, 4096);
    brute.intersect(rays, HitMode::AnyHit, want, nullptr);
    gridrt.intersectTowardsPoint(light, rays, HitMode::AnyHit, got);
    EXPECT_EQ(hitOrMissDiffers(want, got), 0u) << "light batch " << batch;
  }
}

}  // namespace
}  // namespace gridrt
