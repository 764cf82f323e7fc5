// Exact triangle/box overlap by the separating axis theorem (Akenine-Moeller 2001,
// "Fast 3D Triangle-Box Overlap Testing"): 3 box normals, the triangle normal and the
// 9 edge cross products. Closed sets: touching counts as overlap. Evaluated in double
// precision on float inputs, so the answer is exact up to double rounding.
#pragma once
#include <glm/glm.hpp>

namespace gridrt {

bool triangleOverlapsBox(const glm::dvec3& box_lo, const glm::dvec3& box_hi, const glm::dvec3& a,
                         const glm::dvec3& b, const glm::dvec3& c);

}  // namespace gridrt
