// Packet culling (host/gridrt/culling/packet_culling.h): a triangle's box on the tangent plane must
// hold the (a, b) of every ray the ray/triangle test reports as hitting it, including the rays that
// the test's rounding lets through just outside the exact triangle; triangles the argument does not
// hold for (a vertex behind the origin, edge-on) are never culled.
#include "packet_culling.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "prepared_triangles.h"
#include "test_support.h"

namespace gridrt {
namespace {

// An orthonormal frame looking from `origin` towards `target`.
GrCullFrame frameTowards(const glm::vec3& origin, const glm::vec3& target) {
  const glm::vec3 f = glm::normalize(target - origin);
  const glm::vec3 helper = std::abs(f.y) < 0.9f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
  const glm::vec3 r = glm::normalize(glm::cross(f, helper));
  const glm::vec3 u = glm::cross(r, f);
  GrCullFrame frame{};
  frame.fx = f.x, frame.fy = f.y, frame.fz = f.z, frame.enabled = 1.0f;
  frame.rx = r.x, frame.ry = r.y, frame.rz = r.z;
  frame.ux = u.x, frame.uy = u.y, frame.uz = u.z;
  return frame;
}

bool inside(const CullBox& box, float a, float b) {
  return a >= box.amin && a <= box.amax && b >= box.bmin && b <= box.bmax;
}

struct Violations {
  size_t hits = 0;     // rays the test reported as hits (t > 0)
  size_t outside = 0;  // ... whose (a, b) lie outside the triangle's box
};

// Random triangles (a third of them nearly edge-on) seen from random origins, and rays
// aimed at their vertices with a tiny random miss, where the test's rounding decides.
Violations countViolations(bool watertight, double error_factor) {
  std::mt19937 rng(1234);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  Violations result;
  for (int trial = 0; trial < 400; ++trial) {
    const glm::vec3 centre(unit(rng) * 50.0f, unit(rng) * 50.0f, unit(rng) * 50.0f);
    const glm::vec3 origin = centre + glm::vec3(unit(rng), unit(rng), unit(rng)) * 20.0f;
    glm::vec3 v[3];
    for (glm::vec3& x : v) x = centre + glm::vec3(unit(rng), unit(rng), unit(rng));
    if (trial % 3 == 0) {
      // Squash the triangle towards the plane through the origin and its first edge.
      const glm::vec3 n = glm::normalize(glm::cross(v[1] - v[0], origin - v[0]));
      v[2] -= n * (glm::dot(v[2] - v[0], n) * 0.999f);
    }
    const GrTriangle tri = prepareTriangle(v, 0, KernelOptions{watertight});
    const GrCullFrame frame = frameTowards(origin, centre);
    std::vector<CullBox> boxes;
    computeCullBoxes(frame, origin, {tri}, boxes, error_factor);
    for (int ray = 0; ray < 3000; ++ray) {
      const float scale = std::ldexp(1.0f, -10 - int(rng() % 14));
      const glm::vec3 target = v[ray % 3] + glm::vec3(unit(rng), unit(rng), unit(rng)) * scale;
      const glm::vec3 d = glm::normalize(target - origin);
      float t, u, w;
      const int hit = test::intersectScalar(tri, origin, d, &t, &u, &w);
      if (!hit || !(t > 0.0f)) continue;
      ++result.hits;
      float a, b;
      cullCoordinates(frame, d.x, d.y, d.z, a, b);
      result.outside += !inside(boxes[0], a, b);
    }
  }
  return result;
}

TEST(PacketCulling, MarginCoversTheTestsRounding) {
  for (bool watertight : {false, true}) {
    const Violations with = countViolations(watertight, kCullErrorFactor);
    EXPECT_GT(with.hits, 100000u);
    EXPECT_EQ(with.outside, 0u) << (watertight ? "watertight" : "Moeller-Trumbore");
    // Without the margin the exact box loses hits the float test reports.
    const Violations without = countViolations(watertight, 0.0);
    EXPECT_GT(without.outside, 0u) << (watertight ? "watertight" : "Moeller-Trumbore");
  }
}

TEST(PacketCulling, TrianglesNotInFrontOrEdgeOnAreNeverCulled) {
  const glm::vec3 origin(0.0f);
  const GrCullFrame frame = frameTowards(origin, glm::vec3(0, 0, -1));
  auto boxOf = [&](glm::vec3 a, glm::vec3 b, glm::vec3 c) {
    const glm::vec3 v[3] = {a, b, c};
    std::vector<CullBox> boxes;
    computeCullBoxes(frame, origin, {prepareTriangle(v, 0)}, boxes);
    return boxes[0];
  };
  const CullBox in_front = boxOf({-1, -1, -5}, {1, -1, -5}, {0, 1, -5});
  EXPECT_TRUE(std::isfinite(in_front.amin) && std::isfinite(in_front.bmax));
  EXPECT_LT(in_front.amax - in_front.amin, 0.5f);
  // One vertex behind the origin: its projection flips, the box would be wrong.
  const CullBox straddling = boxOf({-1, -1, -5}, {1, -1, -5}, {0, 1, 3});
  EXPECT_EQ(straddling.amin, -INFINITY);
  EXPECT_EQ(straddling.bmax, INFINITY);
  // Edge-on: the plane holds the origin, the test's conditioning is unbounded.
  const CullBox edge_on = boxOf({-1, 0, -5}, {1, 0, -5}, {0, 0, -7});
  EXPECT_EQ(edge_on.amin, -INFINITY);
  EXPECT_EQ(edge_on.amax, INFINITY);
}

TEST(PacketCulling, CameraFrameCoversItsRaysButNotRaysAcross) {
  Camera camera;
  camera.world = glm::mat4(1.0f);
  camera.yfov = 1.2f;
  const PinholeView view = PinholeView::of(camera, 640, 480, PixelWindow{});
  const GrCullFrame frame = cullFrameOf(view);
  EXPECT_FLOAT_EQ(frame.fz, -1.0f);
  const float tan_half = std::tan(0.6f);
  // The corner ray of the image is covered; a ray at right angles is not.
  const glm::vec3 corner = glm::normalize(glm::vec3(tan_half * 640.0f / 480.0f, tan_half, -1.0f));
  EXPECT_TRUE(cullFrameCovers(frame, GrRay{0, 0, 0, 0, corner.x, corner.y, corner.z, INFINITY}));
  EXPECT_FALSE(cullFrameCovers(frame, GrRay{0, 0, 0, 0, 1, 0, 0, INFINITY}));
  EXPECT_FALSE(cullFrameCovers(frame, GrRay{0, 0, 0, 0, 0, 0, 1, INFINITY}));
  float a, b;
  cullCoordinates(frame, corner.x, corner.y, corner.z, a, b);
  EXPECT_NEAR(a, tan_half * 640.0f / 480.0f, 1e-5f);
  EXPECT_NEAR(b, tan_half, 1e-5f);
}

}  // namespace
}  // namespace gridrt
