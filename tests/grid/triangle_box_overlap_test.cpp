#include "triangle_box_overlap.h"

#include <gtest/gtest.h>

#include <random>

namespace gridrt {
namespace {

// Cases each separating axis decides: the triangle's bounding box meets the unit box in
// all of them but the first, so only the axes the test makes itself can tell.
TEST(TriangleBoxTest, EachKindOfAxisSeparatesWhereItShould) {
  const glm::dvec3 lo(0.0), hi(1.0);
  auto both = [&](glm::dvec3 a, glm::dvec3 b, glm::dvec3 c) {
    const bool one = triangleOverlapsBox(lo, hi, a, b, c);
    EXPECT_EQ(TriangleBoxTest(a, b, c).overlaps(lo, hi), one);
    return one;
  };
  // A box normal: beside the box.
  EXPECT_FALSE(both({2, 0, 0}, {3, 0, 0}, {2, 1, 0}));
  // Touching a face counts (closed sets).
  EXPECT_TRUE(both({1, 0, 0}, {2, 0, 0}, {1, 1, 1}));
  // The triangle's normal: a plane x + y + z = 3.2 cuts the box's bounding box but not it.
  EXPECT_FALSE(both({3.2, 0, 0}, {0, 3.2, 0}, {0, 0, 3.2}));
  EXPECT_TRUE(both({2.9, 0, 0}, {0, 2.9, 0}, {0, 0, 2.9}));
  // An edge x axis: neither the bounding boxes nor the triangle's plane separate these.
  EXPECT_FALSE(both({0.5, 0.5, 1.5}, {-0.5, 0.25, 1.0}, {1.75, 2.0, 1.5}));
}

// Random triangles and boxes, near the origin and far from it: the many-box test answers
// as the box-centred one but where a box touches the triangle within rounding. Where the
// two differ, the centred test agrees once the box is grown (or shrunk) by a billionth of
// the coordinates' magnitude.
TEST(TriangleBoxTest, AgreesWithTheCentredTestUpToRounding) {
  std::mt19937 random(11);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  int overlapping = 0, disagreements = 0;
  for (double offset : {0.0, 1e4}) {
    for (int trial = 0; trial < 20000; ++trial) {
      const double size = std::exp2(unit(random) * 8.0);
      auto point = [&] {
        return glm::dvec3(offset + unit(random) * size, unit(random) * size, unit(random) * size);
      };
      const glm::dvec3 a = point(), b = point(), c = point();
      const glm::dvec3 centre = point();
      const glm::dvec3 half(std::abs(unit(random)) * size, std::abs(unit(random)) * size,
                            std::abs(unit(random)) * size);
      const glm::dvec3 lo = centre - half, hi = centre + half;
      const bool fast = TriangleBoxTest(a, b, c).overlaps(lo, hi);
      const bool centred = triangleOverlapsBox(lo, hi, a, b, c);
      overlapping += centred;
      if (fast == centred) continue;
      ++disagreements;
      const double delta = 1e-9 * (std::abs(offset) + size);
      if (fast)
        EXPECT_TRUE(triangleOverlapsBox(lo - delta, hi + delta, a, b, c)) << trial;
      else
        EXPECT_FALSE(triangleOverlapsBox(lo + delta, hi - delta, a, b, c)) << trial;
    }
  }
  EXPECT_GT(overlapping, 4000);  // both answers are common
  EXPECT_LT(overlapping, 36000);
  EXPECT_LT(disagreements, 10);
}

}  // namespace
}  // namespace gridrt
