// A prepared triangle from three corners, for tests that build their scenes by hand.
#pragma once
#include <glm/glm.hpp>

#include "prepared_triangles.h"

namespace gridrt::test {

inline GrTriangle tri(glm::vec3 a, glm::vec3 b, glm::vec3 c, int prim) {
  const glm::vec3 v[3] = {a, b, c};
  return prepareTriangle(v, prim);
}

}  // namespace gridrt::test
