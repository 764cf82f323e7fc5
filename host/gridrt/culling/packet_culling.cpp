#include "packet_culling.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

#include "outward_rounding.h"
#include "parallel_loops.h"
#include "prefault.h"
#include "prepared_triangles.h"

namespace gridrt {

namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();
constexpr CullBox kUnculled{-kInf, kInf, -kInf, kInf};

glm::dvec3 forwardOf(const GrCullFrame& f) { return {f.fx, f.fy, f.fz}; }
glm::dvec3 rightOf(const GrCullFrame& f) { return {f.rx, f.ry, f.rz}; }
glm::dvec3 upOf(const GrCullFrame& f) { return {f.ux, f.uy, f.uz}; }

CullBox boxOf(const GrCullFrame& frame, const glm::dvec3& origin, const glm::dvec3 v[3],
              double error_factor) {
  const glm::dvec3 f = forwardOf(frame), r = rightOf(frame), u = upOf(frame);
  // One square root (the farthest vertex) and a division a vertex: this runs for every
  // triangle of every PE whenever the camera moves.
  double a[3], b[3], z_min = std::numeric_limits<double>::infinity(), far2 = 0.0;
  glm::dvec3 w[3];
  for (int i = 0; i < 3; ++i) {
    w[i] = v[i] - origin;
    far2 = std::max(far2, glm::dot(w[i], w[i]));
  }
  const double far = std::sqrt(far2);
  for (int i = 0; i < 3; ++i) {
    const double z = glm::dot(w[i], f);
    if (!(z > kCullMinDepth * far)) return kUnculled;
    z_min = std::min(z_min, z);
    const double inv_z = 1.0 / z;  // a double rounding more: nothing beside the margin
    a[i] = glm::dot(w[i], r) * inv_z;
    b[i] = glm::dot(w[i], u) * inv_z;
  }
  const glm::dvec3 e1 = v[1] - v[0], e2 = v[2] - v[0], e3 = v[2] - v[1];
  const glm::dvec3 n = glm::cross(e1, e2);
  const double edge2 = std::max({glm::dot(e1, e1), glm::dot(e2, e2), glm::dot(e3, e3)});
  const double incidence = std::abs(glm::dot(n, w[0]));
  const double kappa = edge2 * far / incidence;
  double spread = 1.0;
  for (int i = 0; i < 3; ++i) spread = std::max(spread, 1.0 + std::abs(a[i]) + std::abs(b[i]));
  const double margin = error_factor * 0x1p-24 * kappa * (far / z_min) * spread * spread;
  if (!(margin < 1.0)) return kUnculled;  // also NaN/inf: edge-on or degenerate
  return CullBox{floatBelow(std::min({a[0], a[1], a[2]}) - margin),
                 floatAbove(std::max({a[0], a[1], a[2]}) + margin),
                 floatBelow(std::min({b[0], b[1], b[2]}) - margin),
                 floatAbove(std::max({b[0], b[1], b[2]}) + margin)};
}

}  // namespace

GrCullFrame cullFrameOf(const PinholeView& view) {
  // The rows of the camera's rotation are its axes in world space; the camera looks down -z.
  const glm::mat4& m = view.world_to_camera;
  const glm::vec3 right = glm::normalize(glm::vec3(m[0][0], m[1][0], m[2][0]));
  const glm::vec3 up = glm::normalize(glm::vec3(m[0][1], m[1][1], m[2][1]));
  const glm::vec3 forward = -glm::normalize(glm::vec3(m[0][2], m[1][2], m[2][2]));
  GrCullFrame frame{};
  frame.fx = forward.x, frame.fy = forward.y, frame.fz = forward.z, frame.enabled = 1.0f;
  frame.rx = right.x, frame.ry = right.y, frame.rz = right.z;
  frame.ux = up.x, frame.uy = up.y, frame.uz = up.z;
  return frame;
}

void cullCoordinates(const GrCullFrame& c, float dx, float dy, float dz, float& a, float& b) {
  const float w = dx * c.fx + dy * c.fy + dz * c.fz;
  a = (dx * c.rx + dy * c.ry + dz * c.rz) / w;
  b = (dx * c.ux + dy * c.uy + dz * c.uz) / w;
}

void computeCullBoxes(const GrCullFrame& frame, const glm::vec3& origin,
                      const std::vector<GrTriangle>& triangles, std::vector<CullBox>& boxes,
                      double error_factor) {
  reserveFaultedIn(boxes, triangles.size());  // fresh memory: on every core (prefault.h)
  boxes.resize(triangles.size());
  const glm::dvec3 o(origin);
  parallelFor(0LL, (long long)(triangles.size()), [&](long long k) {
    glm::dvec3 v[3];
    triangleVertices(triangles[k], v);
    boxes[k] = boxOf(frame, o, v, error_factor);
  });
}

bool CullPlaneCache::update(const GrCullFrame& frame, const glm::vec3& origin,
                            const std::vector<GrTriangle>& triangles) {
  if (valid_ && std::memcmp(&frame, &frame_, sizeof frame) == 0 && origin == origin_ &&
      boxes_.size() == triangles.size())
    return false;
  computeCullBoxes(frame, origin, triangles, boxes_);
  const size_t stride = triangles.size() + kCullPlanePadding;
  reserveFaultedIn(planes_, 4 * stride);
  planes_.assign(4 * stride, 0.0f);
  parallelFor(0LL, (long long)(boxes_.size()), [&](long long i) {
    planes_[i] = boxes_[i].amin;
    planes_[stride + i] = boxes_[i].amax;
    planes_[2 * stride + i] = boxes_[i].bmin;
    planes_[3 * stride + i] = boxes_[i].bmax;
  });
  frame_ = frame;
  origin_ = origin;
  valid_ = true;
  return true;
}

}  // namespace gridrt
