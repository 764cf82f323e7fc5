// The 16-lane packets the PE kernels run (IntersectCounters::packets, the statistics'
// kernel_packets): every PE's rays in 16s, its last packet padded. For a list batch of
// rays in one octant (the binning starts a packet for each PE and octant) they follow from
// the rays each PE received; for a light bundle batch every blocked ray holds a lane of
// some packet.
#include <gtest/gtest.h>

#include <glm/glm.hpp>
#include <limits>
#include <random>

#include "bounds.h"
#include "default_scene_fixture.h"
#include "gridrt_intersector.h"
#include "uniform_grid.h"

namespace gridrt {
namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();
constexpr uint64_t kLanes = GR_PACKET_LANES;

using PacketCount = test::DefaultSceneTest;

TEST_F(PacketCount, ListBatchOfOneOctantRunsEveryPesRaysInSixteens) {
  const UniformGrid grid = buildUniformGrid(triangles_, sceneBounds(scene_), GridSettings{});
  GridRtIntersector gridrt(*runtime_, grid, PeInterrupt::CameraRays);
  std::mt19937 rng(3);
  std::normal_distribution<float> g;
  std::vector<GrRay> rays;
  for (int k = 0; k < 5000; ++k) {
    const glm::vec3 o = inside(rng);
    const glm::vec3 d = glm::normalize(glm::abs(glm::vec3(g(rng), g(rng), g(rng))));
    rays.push_back(GrRay{o.x, o.y, o.z, 0.0f, d.x, d.y, d.z, kInf});
  }
  std::vector<GrHit> hits;
  gridrt.intersect(rays, HitMode::Closest, hits, nullptr);
  uint64_t want = 0, pairs = 0;
  for (uint64_t pe_rays : gridrt.raysPerPe()) {
    want += (pe_rays + kLanes - 1) / kLanes;
    pairs += pe_rays;
  }
  ASSERT_EQ(pairs, gridrt.counters().list_entries);
  ASSERT_GT(want, 0u);
  EXPECT_EQ(gridrt.counters().packets, want);
}

TEST_F(PacketCount, LightBundleBatchGivesEveryBlockedRayALane) {
  const UniformGrid grid = buildUniformGrid(triangles_, sceneBounds(scene_), GridSettings{});
  GridRtIntersector gridrt(*runtime_, grid, PeInterrupt::CameraRays);
  gridrt.forceLightBundles();
  std::mt19937 rng(11);
  const glm::vec3 light = inside(rng);
  std::vector<GrRay> rays;
  for (int k = 0; k < 5000; ++k) {
    const glm::vec3 o = inside(rng), to = light - o;
    const float distance = glm::length(to);
    const glm::vec3 d = to / distance;
    rays.push_back(GrRay{o.x, o.y, o.z, 0.0f, d.x, d.y, d.z, distance});
  }
  std::vector<GrHit> hits;
  gridrt.intersectTowardsPoint(light, rays, HitMode::AnyHit, hits);
  uint64_t blocked = 0;
  for (const GrHit& h : hits) blocked += h.prim >= 0;
  ASSERT_GT(blocked, 0u);
  EXPECT_GE(gridrt.counters().packets, (blocked + kLanes - 1) / kLanes);
  // Each packet holds at least one ray of its task.
  EXPECT_LE(gridrt.counters().packets, uint64_t(rays.size()) * grid.peCount());
}

}  // namespace
}  // namespace gridrt
