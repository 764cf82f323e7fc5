// Exact triangle/box overlap by the separating axis theorem (Akenine-Moeller 2001,
// "Fast 3D Triangle-Box Overlap Testing"): 3 box normals, the triangle normal and the
// 9 edge cross products. Closed sets: touching counts as overlap. Evaluated in double
// precision on float inputs, so the answer is exact up to double rounding.
#pragma once
#include <glm/glm.hpp>

namespace gridrt {

// One triangle against one box, in the box's centred coordinates.
bool triangleOverlapsBox(const glm::dvec3& box_lo, const glm::dvec3& box_hi, const glm::dvec3& a,
                         const glm::dvec3& b, const glm::dvec3& c);

// One triangle against many boxes (the cells its bounding box meets): the triangle's side of
// the test (its bounding box, its 10 axes besides the box normals and its extent along each)
// is made once, so a box costs 10 projections of its centre and half size. The projections
// are not centred on the box: the answer is exact up to double rounding of the coordinates
// (a few 1e-16 of their magnitude), far below every grid margin (uniform_grid.h).
class TriangleBoxTest {
 public:
  TriangleBoxTest(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c);
  bool overlaps(const glm::dvec3& box_lo, const glm::dvec3& box_hi) const;

 private:
  static constexpr int kAxes = 10;
  glm::dvec3 lo_, hi_;              // the triangle's bounding box
  glm::dvec3 axis_[kAxes];          // its normal, then each edge x each unit axis
  double min_[kAxes], max_[kAxes];  // its extent along each axis
};

}  // namespace gridrt
