// An axis-aligned box.
#pragma once
#include <glm/glm.hpp>
#include <limits>

namespace gridrt {

struct Bounds {
  glm::vec3 lo{std::numeric_limits<float>::infinity()};
  glm::vec3 hi{-std::numeric_limits<float>::infinity()};

  void grow(const glm::vec3& p) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  bool empty() const { return !(lo.x <= hi.x && lo.y <= hi.y && lo.z <= hi.z); }
  glm::vec3 extent() const { return hi - lo; }
  glm::vec3 center() const { return (lo + hi) * 0.5f; }
};

}  // namespace gridrt
