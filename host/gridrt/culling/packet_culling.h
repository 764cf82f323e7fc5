// Packet culling for rays that share an origin (camera rays): the PE kernel skips a
// triangle for a 16-ray packet when the packet's directions and the triangle's outline,
// both put on one tangent plane, have disjoint boxes. The triangle's box is grown by a
// bound on the rounding of the ray/triangle test, so every triangle the test could report
// as hit for some lane is still tested: the hits stay bit-identical to brute force.
//
// A direction d lands at (a, b) = (d.r / d.f, d.u / d.f) on the plane of the frame
// (GrCullFrame: forward f, right r, up u). A ray from the origin hits the triangle's plane
// at a point whose (a, b) is its own, and a triangle in front of the origin (every
// vertex with w.f > 0, w = vertex - origin) projects onto the triangle of its projected
// vertices, so a ray through it has (a, b) inside that triangle's box.
#pragma once
#include <glm/glm.hpp>
#include <vector>

#include "gridrt_types.h"
#include "pinhole_view.h"
#include "segment_culling.h"

namespace gridrt {

// Culling stays off for a batch with a ray more than acos(0.1) ~ 84 degrees off the
// frame's forward: (a, b) grow without bound near 90 degrees.
constexpr double kCullMinCos = 0.1;
// A triangle's box is grown by kCullErrorFactor * 2^-24 * kappa * scale * spread^2, where
// kappa = longest edge^2 * farthest vertex / |n . w0| bounds the conditioning of the
// ray/triangle test (1 / (sin of the smallest angle * cos of the incidence)), scale =
// farthest / nearest vertex depth and spread = 1 + max |a| + |b| (the projection's
// slope). Rounding analysis of Moeller-Trumbore gives a factor of about 3 (1 suffices in
// the test); 64 is margin. As kappa, scale, spread >= 1 the margin is at least 64 ulps *
// spread, which also covers the kernel's float (a, b) of a lane (<= 34 ulps * spread with
// kCullMinCos). Without it PacketCulling.MarginCoversTheTestsRounding finds hits outside.
constexpr double kCullErrorFactor = 64.0;
// A vertex nearer to the origin's plane than this fraction of its distance makes the
// triangle unculled (the projection's slope is unbounded there).
constexpr double kCullMinDepth = 1e-3;

// A triangle's box on the tangent plane, grown by its rounding margin; +-infinity where
// the triangle cannot be culled (a vertex not in front, or ill-conditioned).
struct CullBox {
  float amin, amax, bmin, bmax;
};

// The camera's frame (forward, right, up in world space), culling enabled.
GrCullFrame cullFrameOf(const PinholeView& view);

// A lane's (a, b) exactly as the PE kernel computes it in float (kernels/gridrt_bundles.cl).
void cullCoordinates(const GrCullFrame& frame, float dx, float dy, float dz, float& a, float& b);

// True when the ray's direction is within kCullMinCos of the frame's forward; the kernel
// may cull a batch only when the frame covers all its rays.
inline bool cullFrameCovers(const GrCullFrame& f, const GrRay& ray) {
  const float along = ray.dx * f.fx + ray.dy * f.fy + ray.dz * f.fz;
  const float length2 = ray.dx * ray.dx + ray.dy * ray.dy + ray.dz * ray.dz;
  return along > 0.0f && along * along >= float(kCullMinCos * kCullMinCos) * length2;
}

// The conservative box of every triangle (in the order given) seen from `origin`.
// error_factor is kCullErrorFactor but for tests.
void computeCullBoxes(const GrCullFrame& frame, const glm::vec3& origin,
                      const std::vector<GrTriangle>& triangles, std::vector<CullBox>& boxes,
                      double error_factor = kCullErrorFactor);

// Rays that end at the origin instead of starting there (shadow rays towards a point
// light, light_culling.h), each from its own point: a ray's line passes within `miss` of
// the origin, |o|_1 + |tmax| <= ray_reach and |d| >= min_length. Their boxes are grown by
// what those bounds allow (boxesOfBlock in packet_culling.cpp); segment_error_factor is
// kSegmentCullErrorFactor but for tests.
struct TowardsOrigin {
  double miss = 0.0, ray_reach = 0.0, min_length = 1.0;
  double segment_error_factor = kSegmentCullErrorFactor;
};

// The boxes of `triangles` for rays towards `origin` (TowardsOrigin). For tests.
void computeTowardsOriginBoxes(const GrCullFrame& frame, const glm::vec3& origin,
                               const TowardsOrigin& towards,
                               const std::vector<GrTriangle>& triangles,
                               std::vector<CullBox>& boxes, double error_factor = kCullErrorFactor);

// Their four planes (as CullPlaneCache's) from `planes` on, each `stride` floats apart, on
// all cores; the padding is the caller's.
void writeTowardsOriginBoxPlanes(const GrCullFrame& frame, const glm::vec3& origin,
                                 const TowardsOrigin& towards, const GrTriangle* triangles,
                                 size_t count, float* planes, size_t stride);

// The padding after each plane of boxes: the PE kernel reads a float16 of boxes at a time,
// so its last load of a PE may run 15 boxes past the end.
constexpr size_t kCullPlanePadding = GR_PACKET_LANES;

// The boxes as the PE kernel reads them: four planes (amin, amax, bmin, bmax), each
// stride() = triangles + kCullPlanePadding floats long. Recomputed only when the frame or the
// origin changes (a camera renders many frames from one place).
class CullPlaneCache {
 public:
  // True when the planes were recomputed (a device copy is then stale).
  bool update(const GrCullFrame& frame, const glm::vec3& origin, const GrTriangle* triangles,
              size_t count);
  const std::vector<float>& planes() const { return planes_; }
  size_t stride() const { return planes_.size() / 4; }

 private:
  bool valid_ = false;
  GrCullFrame frame_{};
  glm::vec3 origin_{0.0f};
  std::vector<float> planes_;
};

}  // namespace gridrt
