// Secondary ray origins, where methods fail. A fixed world-space offset (epsilon = 1e-4)
// is below one float ulp of large coordinates, so the spawned ray starts on (or under)
// its own surface and hits it again (acne); at small scales it jumps past nearby
// occluders (light leaks). The robust offset (Waechter & Binder, offsetRayOrigin) must
// do neither at any scale. Each test records by how much the fixed offset fails.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <random>

#include "brute_intersector.h"
#include "cl_runtime.h"
#include "default_scene.h"
#include "moller_trumbore.h"
#include "prepared_triangles.h"
#include "reference_intersector.h"
#include "whitted_shading.h"

namespace gridrt {
namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();

void record(const std::string& key, size_t value) {
  ::testing::Test::RecordProperty(key, std::to_string(value));
  std::printf("  %-40s %zu\n", key.c_str(), value);
}

// A direction in the hemisphere around n with cos(theta) = c (c small: grazing).
glm::vec3 hemisphereDirection(const glm::vec3& n, float c, float phi) {
  glm::vec3 a = std::fabs(n.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
  glm::vec3 t = glm::normalize(glm::cross(n, a)), b = glm::cross(n, t);
  float s = std::sqrt(std::max(0.0f, 1.0f - c * c));
  return glm::normalize(c * n + s * (std::cos(phi) * t + std::sin(phi) * b));
}

// Hit points computed the way the renderer does (p = o + t d after a primary hit from a
// camera a few triangle sizes away); rays spawned above and below the surface (reflection
// and refraction) in directions down to grazing; a self-hit is the ray hitting its own
// triangle again (the same Moeller-Trumbore the kernels run, t > 0 as tmin = 0).
TEST(RayOffset, SpawnedRaysNeverHitTheirOwnTriangleAtAnyScale) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> U(-1.0f, 1.0f), U01(0.0f, 1.0f);
  const RayOffset robust{true, 1e-4f}, fixed{false, 1e-4f};
  size_t total_robust = 0, tested = 0;
  for (double scale : {1e-6, 1e-4, 1e-2, 1.0, 1e2, 1e4, 1e6}) {
    size_t self[2] = {0, 0}, rays = 0;  // robust, epsilon
    for (int k = 0; k < 600; ++k) {
      glm::vec3 a(U(rng), U(rng), U(rng)), b(U(rng), U(rng), U(rng)), c(U(rng), U(rng), U(rng));
      // Half the triangles around the origin, half offset by 3 sizes (all one sign).
      glm::vec3 shift = k % 2 ? glm::vec3(3.0f) : glm::vec3(0.0f);
      a = float(scale) * (a + shift);
      b = float(scale) * (b + shift);
      c = float(scale) * (c + shift);
      glm::vec3 e1 = b - a, e2 = c - a, ng = glm::cross(e1, e2);
      if (!(glm::length(ng) > 0.0f)) continue;
      ng = glm::normalize(ng);
      float w1 = U01(rng), w2 = U01(rng);
      if (w1 + w2 > 1.0f) w1 = 1.0f - w1, w2 = 1.0f - w2;
      glm::vec3 target = a + w1 * e1 + w2 * e2;
      glm::vec3 eye = target + float(3.0 * scale) * hemisphereDirection(ng, 0.3f + 0.7f * U01(rng),
                                                                        6.2832f * U01(rng));
      glm::vec3 d = glm::normalize(target - eye);
      float t, u, v;
      if (!gr_intersect_mt(eye.x, eye.y, eye.z, d.x, d.y, d.z, a.x, a.y, a.z, e1.x, e1.y, e1.z,
                           e2.x, e2.y, e2.z, &t, &u, &v))
        continue;
      glm::vec3 p = eye + t * d;
      glm::vec3 n = glm::dot(ng, d) > 0.0f ? -ng : ng;  // facing the camera
      for (int j = 0; j < 16; ++j) {
        float cos_theta = std::pow(10.0f, -4.0f * U01(rng));  // 1e-4 .. 1
        float side = j % 2 ? -1.0f : 1.0f;                    // reflection / refraction
        glm::vec3 dir = hemisphereDirection(side * n, cos_theta, 6.2832f * U01(rng));
        for (int m = 0; m < 2; ++m) {
          glm::vec3 o = offsetRayOrigin(p, side * n, eye, m ? fixed : robust);
          float th;
          self[m] += gr_intersect_mt(o.x, o.y, o.z, dir.x, dir.y, dir.z, a.x, a.y, a.z, e1.x, e1.y,
                                     e1.z, e2.x, e2.y, e2.z, &th, &u, &v) &&
                     th > 0.0f;
        }
        ++rays;
      }
    }
    const char* names[2] = {"robust", "epsilon"};
    for (int m = 0; m < 2; ++m) {
      char key[64];
      std::snprintf(key, sizeof key, "self_hits_scale_%g_%s", scale, names[m]);
      record(key, self[m]);
    }
    total_robust += self[0];
    tested += rays;
    if (scale >= 1e4) {
      EXPECT_GT(self[1], 0u) << "epsilon 1e-4 should fail at scale " << scale;
    }
  }
  EXPECT_GT(tested, 50000u);
  EXPECT_EQ(total_robust, 0u);
}

// The same small scene (a floor, a box floating above it, a point light) scaled and
// translated; shadow rays from floor points seen by a camera, as the renderer spawns them.
// Exact answer: the double-precision test of the same float ray against the box.
class ShadowSweep : public ::testing::Test {
 protected:
  void SetUp() override {
    if (listDevices().empty()) GTEST_SKIP() << "no OpenCL device: install pocl-opencl-icd";
    runtime_ = std::make_unique<ClRuntime>("");
  }
  std::unique_ptr<ClRuntime> runtime_;
};

// Floor points closer than this (times the scene scale) to the outline of the box's
// shadow are not judged: there any displacement of the origin, which every offset needs,
// may rightly flip the answer. Offsets of 1% of the scene and more still count.
constexpr double kShadowBand = 1e-2;

struct ShadowCounts {
  size_t points = 0, acne = 0, leaks = 0;
};

TEST_F(ShadowSweep, ShadowRaysMatchTheExactReferenceAtEveryScale) {
  for (double translation : {0.0, 1e2, 1e5}) {
    for (double scale : {1e-4, 1e-2, 1.0, 1e2, 1e4}) {
      auto X = [&](glm::dvec3 p) { return glm::vec3(p * scale + glm::dvec3(translation)); };
      Scene scene;
      int m = shapes::addMaterial(scene, Material{});
      shapes::addRect(scene, X({0, 0, 0}), glm::vec3(glm::dvec3(0, 0, 1) * scale),
                      glm::vec3(glm::dvec3(1, 0, 0) * scale), m);  // floor y = 0, normal +y
      size_t floor_tris = scene.triangleCount();
      shapes::addBox(scene, X({0.1, 0.4, -0.05}), glm::vec3(glm::dvec3(0.3, 0.2, 0.25) * scale),
                     0.3f, m);
      glm::vec3 light = X({0.45, 2.0, 0.3});
      glm::vec3 eye = X({0.2, 2.5, 3.0});
      auto tris = prepareTriangles(scene);
      // The scene's float vertices, in double, for the exact test.
      std::vector<std::array<glm::dvec3, 3>> box;
      for (size_t t = floor_tris; t < scene.triangleCount(); ++t)
        box.push_back({glm::dvec3(scene.positions[3 * t]), glm::dvec3(scene.positions[3 * t + 1]),
                       glm::dvec3(scene.positions[3 * t + 2])});
      auto exactOccluded = [&](const glm::dvec3& pe) {
        glm::dvec3 dl = glm::dvec3(light) - pe;
        double dlen = glm::length(dl);
        for (const auto& b : box) {
          double t, u, v;
          if (intersectTriangleDouble(pe, dl / dlen, b[0], b[1] - b[0], b[2] - b[0], t, u, v) &&
              t > 0.0 && t < dlen)
            return true;
        }
        return false;
      };
      // Floor points seen by the camera on a 48 x 48 lattice.
      std::vector<GrRay> primary;
      for (int i = 0; i < 48; ++i)
        for (int j = 0; j < 48; ++j) {
          glm::vec3 target = X({-0.98 + 1.96 * i / 47.0, 0.0, -0.98 + 1.96 * j / 47.0});
          glm::vec3 d = glm::normalize(target - eye);
          primary.push_back(GrRay{eye.x, eye.y, eye.z, 0.0f, d.x, d.y, d.z, kInf});
        }
      BruteIntersector brute(*runtime_, tris);
      std::vector<GrHit> hits;
      brute.intersect(primary, HitMode::Closest, hits, nullptr);
      for (int method = 0; method < 2; ++method) {  // robust, epsilon
        RayOffset offset{method == 0, 1e-4f};
        std::vector<GrRay> shadow;
        std::vector<char> exact;
        for (size_t r = 0; r < primary.size(); ++r) {
          if (hits[r].prim < 0 || size_t(hits[r].prim) >= floor_tris) continue;
          const GrRay& q = primary[r];
          glm::vec3 p = glm::vec3(q.ox, q.oy, q.oz) + hits[r].t * glm::vec3(q.dx, q.dy, q.dz);
          glm::vec3 o = offsetRayOrigin(p, {0, 1, 0}, eye, offset);
          glm::vec3 to = light - p;
          float dist = glm::length(to);
          glm::vec3 d = to / dist;
          shadow.push_back(GrRay{o.x, o.y, o.z, 0.0f, d.x, d.y, d.z, dist});
          // Exact: the true hit point (double) towards the light, against the box. Points
          // within kShadowBand of the shadow's outline are not judged.
          glm::dvec3 po(q.ox, q.oy, q.oz), pd(q.dx, q.dy, q.dz);
          double floor_y = double(scene.positions[0].y);
          glm::dvec3 pe = po + (floor_y - po.y) / pd.y * pd;
          bool occluded = exactOccluded(pe);
          double band = kShadowBand * scale;
          if (exactOccluded(pe + glm::dvec3(band, 0, 0)) != occluded ||
              exactOccluded(pe - glm::dvec3(band, 0, 0)) != occluded ||
              exactOccluded(pe + glm::dvec3(0, 0, band)) != occluded ||
              exactOccluded(pe - glm::dvec3(0, 0, band)) != occluded) {
            shadow.pop_back();
            continue;
          }
          exact.push_back(occluded);
        }
        std::vector<GrHit> sh;
        brute.intersect(shadow, HitMode::AnyHit, sh, nullptr);
        ShadowCounts c;
        size_t occluded = 0;
        for (size_t s = 0; s < shadow.size(); ++s) {
          bool got = sh[s].prim >= 0;
          c.acne += got && !exact[s];
          c.leaks += !got && exact[s];
          occluded += exact[s];
        }
        c.points = shadow.size();
        char key[96];
        std::snprintf(key, sizeof key, "T%g_scale%g_%s", translation, scale,
                      method == 0 ? "robust" : "epsilon");
        std::printf("  %-34s points %zu (occluded %zu) acne %zu leaks %zu\n", key, c.points,
                    occluded, c.acne, c.leaks);
        RecordProperty(std::string(key) + "_acne", std::to_string(c.acne));
        RecordProperty(std::string(key) + "_leaks", std::to_string(c.leaks));
        // Only where the scene survives in float: the box's smallest feature (0.4 scale)
        // spans at least ~1000 ulps of the translation. Beyond, it is recorded only.
        if (translation > 1e3 * scale) continue;
        ASSERT_GT(c.points, 1000u) << key;  // the band leaves most points judged
        ASSERT_GT(occluded, 50u) << key;
        if (method == 0) {
          EXPECT_EQ(c.acne, 0u) << key;
          EXPECT_EQ(c.leaks, 0u) << key;
        }
        if (method == 1 && scale == 1e-4) {
          EXPECT_GT(c.leaks, 0u) << key;
        }
        if (method == 1 && scale == 1e4 && translation == 0.0) {
          EXPECT_GT(c.acne, 0u) << key;
        }
      }
    }
  }
}

// A concave corner: a floor (y = 0) meeting a wall (x = 0), a point light in the room
// they bound, and floor and wall points ever closer to the seam (1e-1 .. 1e-7 of the
// scene size), seen by a camera, at several scales and translations. Every point is lit:
// the segment to the light never crosses the other surface's plane. But p = o + t d may
// round to just behind the neighbouring surface, which a shadow ray starting at tmin = 0
// then crosses at once: it must start at rayOffsetDistance, as the renderer's do. With
// the watertight test such acne blackened 57 pixels along the default room's seams.
TEST_F(ShadowSweep, ShadowRaysAtAConcaveCornerAreNotBlockedByTheOtherSurface) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> U(-0.9f, 0.9f);
  size_t judged = 0, acne = 0, acne_from_zero = 0;
  for (bool watertight : {false, true}) {
    const KernelOptions kernel{watertight};
    for (double translation : {0.0, 1e2}) {
      for (double scale : {1e-2, 1.0, 1e2}) {
        auto X = [&](glm::dvec3 p) { return glm::vec3(p * scale + glm::dvec3(translation)); };
        auto S = [&](glm::dvec3 v) { return glm::vec3(v * scale); };
        Scene scene;
        int m = shapes::addMaterial(scene, Material{});
        shapes::addRect(scene, X({-0.5, 0, 0}), S({0, 0, 1}), S({0.5, 0, 0}), m);  // floor, +y
        shapes::addRect(scene, X({0, 0.5, 0}), S({0, 0, 1}), S({0, 0.5, 0}), m);   // wall, -x
        const glm::vec3 light = X({-0.5, 0.6, 0.2}), eye = X({-2.0, 1.5, 0.4});
        BruteIntersector brute(*runtime_, prepareTriangles(scene, kernel), kernel);
        std::vector<GrRay> primary;
        for (int k = 0; k < 4000; ++k) {
          const double near = std::pow(10.0, -1.0 - 6.0 * (k / 2) / 2000.0);  // to the seam
          const glm::dvec3 target =
              k % 2 ? glm::dvec3(-near, 0, U(rng)) : glm::dvec3(0, near, U(rng));
          const glm::vec3 d = glm::normalize(X(target) - eye);
          primary.push_back(GrRay{eye.x, eye.y, eye.z, 0.0f, d.x, d.y, d.z, kInf});
        }
        std::vector<GrHit> hits;
        brute.intersect(primary, HitMode::Closest, hits, nullptr);
        std::vector<GrRay> shadow;
        for (size_t r = 0; r < primary.size(); ++r) {
          if (hits[r].prim < 0) continue;
          const GrRay& q = primary[r];
          const glm::vec3 o(q.ox, q.oy, q.oz), p = o + hits[r].t * glm::vec3(q.dx, q.dy, q.dz);
          const glm::vec3 n = hits[r].prim < 2 ? glm::vec3(0, 1, 0) : glm::vec3(-1, 0, 0);
          const RayOffset robust{true, 1e-4f};
          const glm::vec3 start = offsetRayOrigin(p, n, eye, robust), to = light - p;
          const float distance = glm::length(to);
          const glm::vec3 d = to / distance;
          shadow.push_back(GrRay{start.x, start.y, start.z, rayOffsetDistance(p, eye, robust), d.x,
                                 d.y, d.z, distance});
        }
        std::vector<GrHit> blocked;
        brute.intersect(shadow, HitMode::AnyHit, blocked, nullptr);
        size_t here = 0, here_from_zero = 0;
        for (const GrHit& b : blocked) here += b.prim >= 0;
        for (GrRay& ray : shadow) ray.tmin = 0.0f;
        brute.intersect(shadow, HitMode::AnyHit, blocked, nullptr);
        for (const GrHit& b : blocked) here_from_zero += b.prim >= 0;
        std::printf("  %s T%g scale %g: %zu points, blocked %zu (from tmin 0: %zu)\n",
                    watertight ? "watertight" : "mt", translation, scale, shadow.size(), here,
                    here_from_zero);
        EXPECT_GT(shadow.size(), 3500u);
        judged += shadow.size();
        acne += here;
        acne_from_zero += here_from_zero;
      }
    }
  }
  RecordProperty("acne_from_tmin_zero", std::to_string(acne_from_zero));
  EXPECT_EQ(acne, 0u) << "of " << judged << " lit points";
  EXPECT_GT(acne_from_zero, 0u) << "the case no longer shows the failure it guards against";
}

}  // namespace
}  // namespace gridrt
