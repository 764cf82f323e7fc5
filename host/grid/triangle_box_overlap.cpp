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

namespace gridrt {

TriangleBoxTest::TriangleBoxTest(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c)
    : lo_(glm::min(a, glm::min(b, c))), hi_(glm::max(a, glm::max(b, c))) {
  const glm::dvec3 e[3] = {b - a, c - b, a - c};
  axis_[0] = glm::cross(e[0], e[1]);
  int k = 1;
  for (const glm::dvec3& edge : e) {  // unit x edge, without multiplying by 0 and 1
    axis_[k++] = glm::dvec3(0.0, -edge.z, edge.y);
    axis_[k++] = glm::dvec3(edge.z, 0.0, -edge.x);
    axis_[k++] = glm::dvec3(-edge.y, edge.x, 0.0);
  }
  for (k = 0; k < kAxes; ++k) {
    const double p0 = glm::dot(axis_[k], a), p1 = glm::dot(axis_[k], b), p2 = glm::dot(axis_[k], c);
    min_[k] = std::min({p0, p1, p2});
    max_[k] = std::max({p0, p1, p2});
  }
}

bool TriangleBoxTest::overlaps(const glm::dvec3& box_lo, const glm::dvec3& box_hi) const {
  // Box face normals: the bounding boxes (exact).
  for (int k = 0; k < 3; ++k)
    if (lo_[k] > box_hi[k] || hi_[k] < box_lo[k]) return false;
  const glm::dvec3 center = (box_lo + box_hi) * 0.5, h = (box_hi - box_lo) * 0.5;
  for (int k = 0; k < kAxes; ++k) {
    const glm::dvec3& axis = axis_[k];
    const double at = glm::dot(axis, center);
    const double r = h.x * std::fabs(axis.x) + h.y * std::fabs(axis.y) + h.z * std::fabs(axis.z);
    if (min_[k] > at + r || max_[k] < at - r) return false;
  }
  return true;
}

}  // namespace gridrt
