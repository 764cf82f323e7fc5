// The Phong highlights in lanes (host/render/phong_highlights.h): the power within its
// tolerance of the exact one over the whole range of Phong exponents, an exponent of 1
// exact, a surface turned away 0, and the 16 lanes bit for bit one hit's highlight.
#include "phong_highlights.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>

#include "test_support.h"

namespace {

using namespace gridrt;

using test::sameBits;

// The largest relative error of phongHighlight against pow in double over rv and
// exponents spread log-uniformly across (0, 1] and [1, 10000], where the exact power is
// at least kHighlightFloor; and the largest absolute error below it.
struct Errors {
  double relative = 0.0, absolute_below_floor = 0.0;
};

Errors highlightErrors() {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  Errors e;
  for (int k = 0; k < 200000; ++k) {
    // rv from 1e-8 to 1, most of them near 1 where highlights show (1 - 10^-u).
    const float rv = k % 2 ? float(std::pow(10.0, -8.0 * unit(rng)))
                           : float(1.0 - std::pow(10.0, -7.0 * unit(rng)));
    const float exponent = float(std::pow(10.0, 4.0 * unit(rng)));
    const double exact = std::pow(double(rv), double(exponent));
    const double got = phongHighlight(rv, exponent);
    if (exact >= kHighlightFloor)
      e.relative = std::max(e.relative, std::fabs(got - exact) / exact);
    else
      e.absolute_below_floor = std::max(e.absolute_below_floor, std::fabs(got - exact));
  }
  return e;
}

TEST(PhongHighlights, PowerWithinItsToleranceOfTheExactOne) {
  const Errors e = highlightErrors();
  std::printf("largest relative error %.3g, absolute below the floor %.3g\n", e.relative,
              e.absolute_below_floor);
  EXPECT_LE(e.relative, kHighlightRelativeError);
  EXPECT_LE(e.absolute_below_floor, kHighlightFloor);
}

TEST(PhongHighlights, ExponentOneIsRvAndATurnedAwaySurfaceIsDark) {
  for (const float rv : {1e-30f, 1e-7f, 0.3f, 0.999999f, 1.0f})
    EXPECT_TRUE(sameBits(phongHighlight(rv, 1.0f), rv)) << rv;
  for (const float exponent : {1.0f, 2.0f, 10000.0f}) {
    EXPECT_EQ(phongHighlight(0.0f, exponent), 0.0f);
    EXPECT_EQ(phongHighlight(1.0f, exponent), 1.0f);
  }
}

// rv in float against the same formula in double: a few roundings of values up to 3 in
// magnitude (two dot products and a reflection) stay well below this.
constexpr double kRvTolerance = 1e-6;

// Random hits and lights: rv is the one-hit code's max(0, reflect(-l, n) . -d) (to float
// rounding: here in double), and each lane's highlight is phongHighlight of its rv, bit for
// bit, whatever its neighbours.
TEST(PhongHighlights, LanesEqualOneHitBitForBit) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f), e(0.0f, 4.0f);
  size_t lit = 0;
  for (int block = 0; block < 2000; ++block) {
    SurfaceLanes s{};
    LightLanes light{};
    float exponent[kSurfaceLanes];
    for (int k = 0; k < kSurfaceLanes; ++k) {
      const glm::vec3 n = glm::normalize(glm::vec3(u(rng), u(rng), u(rng)));
      const glm::vec3 d = glm::normalize(glm::vec3(u(rng), u(rng), u(rng)));
      const glm::vec3 l = glm::normalize(glm::vec3(u(rng), u(rng), u(rng)));
      s.nx[k] = n.x, s.ny[k] = n.y, s.nz[k] = n.z;
      s.dx[k] = d.x, s.dy[k] = d.y, s.dz[k] = d.z;
      light.lx[k] = l.x, light.ly[k] = l.y, light.lz[k] = l.z;
      exponent[k] = k % 4 == 0 ? 1.0f : std::pow(10.0f, e(rng));
    }
    computeHighlights(s, exponent, light);
    for (int k = 0; k < kSurfaceLanes; ++k) {
      const glm::dvec3 n(s.nx[k], s.ny[k], s.nz[k]), d(s.dx[k], s.dy[k], s.dz[k]);
      const glm::dvec3 l(light.lx[k], light.ly[k], light.lz[k]);
      const glm::dvec3 r = -l - 2.0 * glm::dot(-l, n) * n;
      const double rv = std::max(0.0, glm::dot(r, -d));
      ASSERT_NEAR(light.rv[k], rv, kRvTolerance) << "block " << block << " lane " << k;
      ASSERT_TRUE(sameBits(light.highlight[k], phongHighlight(light.rv[k], exponent[k])))
          << "block " << block << " lane " << k;
      lit += light.highlight[k] > 0.0f;
    }
  }
  EXPECT_GT(lit, 2000u * kSurfaceLanes / 4);  // about half the lanes face the light
}

}  // namespace
