#include "triangle_box_overlap.h"

#include <algorithm>
#include <cmath>

namespace gridrt {

namespace {

// Is `axis` a separating axis for the triangle (v0,v1,v2, box-centred) and the box of
// half size h? A zero axis (parallel edges) separates nothing.
bool separates(const glm::dvec3& axis, const glm::dvec3& v0, const glm::dvec3& v1,
               const glm::dvec3& v2, const glm::dvec3& h) {
  double p0 = glm::dot(axis, v0), p1 = glm::dot(axis, v1), p2 = glm::dot(axis, v2);
  double r = h.x * std::fabs(axis.x) + h.y * std::fabs(axis.y) + h.z * std::fabs(axis.z);
  return std::min({p0, p1, p2}) > r || std::max({p0, p1, p2}) < -r;
}

}  // namespace

bool triangleOverlapsBox(const glm::dvec3& box_lo, const glm::dvec3& box_hi, const glm::dvec3& a,
                         const glm::dvec3& b, const glm::dvec3& c) {
  glm::dvec3 center = (box_lo + box_hi) * 0.5;
  glm::dvec3 h = (box_hi - box_lo) * 0.5;
  glm::dvec3 v0 = a - center, v1 = b - center, v2 = c - center;
  // Box face normals: the triangle's bounding box against the box.
  for (int k = 0; k < 3; ++k) {
    double lo = std::min({v0[k], v1[k], v2[k]}), hi = std::max({v0[k], v1[k], v2[k]});
    if (lo > h[k] || hi < -h[k]) return false;
  }
  glm::dvec3 e[3] = {v1 - v0, v2 - v1, v0 - v2};
  if (separates(glm::cross(e[0], e[1]), v0, v1, v2, h)) return false;
  const glm::dvec3 unit[3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  for (const auto& edge : e)
    for (const auto& u : unit)
      if (separates(glm::cross(u, edge), v0, v1, v2, h)) return false;
  return true;
}

}  // namespace gridrt
