// Keyframe interpolation against values computed by hand: each mode, inside the keys and
// clamped outside them, the quaternion's shorter arc, and equal keys.
#include "keyframe_interpolation.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace gridrt {
namespace {

// Rounding of a few double operations on numbers of order 1 (slerp's sines and cosines).
constexpr double kDoubleRounding = 1e-14;

KeyframeTrack track(Interpolation mode, int width, std::vector<double> times,
                    std::vector<double> values, bool quaternion = false) {
  KeyframeTrack t;
  t.interpolation = mode;
  t.width = width;
  t.times = std::move(times);
  t.values = std::move(values);
  t.quaternion = quaternion;
  return t;
}

using Values = std::vector<double>;

TEST(KeyframeInterpolation, StepHoldsEachKeyUntilTheNext) {
  const KeyframeTrack t = track(Interpolation::Step, 1, {0, 1, 2}, {0, 10, 20});
  EXPECT_EQ(sampleTrack(t, 0.0), Values{0});
  EXPECT_EQ(sampleTrack(t, 0.999), Values{0});
  EXPECT_EQ(sampleTrack(t, 1.0), Values{10});
  EXPECT_EQ(sampleTrack(t, 1.5), Values{10});
  EXPECT_EQ(sampleTrack(t, 2.0), Values{20});
}

TEST(KeyframeInterpolation, LinearBlendsTheTwoKeysAroundTheTime) {
  // Unequal intervals: 0..2 then 2..3.
  const KeyframeTrack t = track(Interpolation::Linear, 3, {0, 2, 3}, {0, 0, 0, 4, 8, -4, 10, 8, 0});
  EXPECT_EQ(sampleTrack(t, 0.5), (Values{1, 2, -1}));  // a quarter of the first interval
  EXPECT_EQ(sampleTrack(t, 2.0), (Values{4, 8, -4}));
  EXPECT_EQ(sampleTrack(t, 2.5), (Values{7, 8, -2}));  // half of the second
}

TEST(KeyframeInterpolation, EveryModeClampsBeforeTheFirstAndAfterTheLastKey) {
  for (Interpolation mode : {Interpolation::Step, Interpolation::Linear}) {
    const KeyframeTrack t = track(mode, 1, {1, 2}, {5, 7});
    EXPECT_EQ(sampleTrack(t, -3.0), Values{5});
    EXPECT_EQ(sampleTrack(t, 1.0), Values{5});
    EXPECT_EQ(sampleTrack(t, 2.0), Values{7});
    EXPECT_EQ(sampleTrack(t, 40.0), Values{7});
  }
  // CUBICSPLINE clamps to the keys' values, not to their tangents.
  const KeyframeTrack cubic = track(Interpolation::CubicSpline, 1, {1, 2}, {9, 5, 9, 9, 7, 9});
  EXPECT_EQ(sampleTrack(cubic, 0.0), Values{5});
  EXPECT_EQ(sampleTrack(cubic, 3.0), Values{7});
  // A single key holds at every time.
  const KeyframeTrack single = track(Interpolation::Linear, 1, {0.5}, {3});
  EXPECT_EQ(sampleTrack(single, 0.0), Values{3});
  EXPECT_EQ(sampleTrack(single, 9.0), Values{3});
}

TEST(KeyframeInterpolation, CubicSplineIsTheHermiteCurveOfValuesAndScaledTangents) {
  // Keys at 0 and 2: v0 = 1 with out-tangent b0 = 1, v1 = 3 with in-tangent a1 = -1 (per
  // second). At t = 1 (u = 1/2): h00 = h01 = 1/2, h10 = 1/8, h11 = -1/8, the tangents
  // scaled by the interval 2: 0.5 + 0.125 * 2 * 1 + 0.5 * 3 - 0.125 * 2 * -1 = 2.5.
  const KeyframeTrack t = track(Interpolation::CubicSpline, 1, {0, 2}, {0, 1, 1, -1, 3, 0});
  EXPECT_EQ(sampleTrack(t, 1.0), Values{2.5});
  // At t = 0.5 (u = 1/4): h00 = 27/32, h10 = 9/64, h01 = 5/32, h11 = -3/64:
  // 27/32 + 9/64 * 2 + 15/32 + 3/64 * 2 = 1.6875.
  EXPECT_EQ(sampleTrack(t, 0.5), Values{1.6875});
}

TEST(KeyframeInterpolation, CubicSplineRotationsAreNormalised) {
  // Values (0,0,0,1) and (0,0,1,0), zero tangents: halfway the curve gives (0,0,.5,.5).
  const KeyframeTrack t =
      track(Interpolation::CubicSpline, 4, {0, 1},
            {0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0, 0, 0}, true);
  const Values q = sampleTrack(t, 0.5);
  const double h = std::sqrt(0.5);
  EXPECT_NEAR(q[2], h, kDoubleRounding);
  EXPECT_NEAR(q[3], h, kDoubleRounding);
}

glm::dvec4 aboutZ(double degrees) {
  const double half = degrees * 3.14159265358979323846 / 360.0;
  return {0, 0, std::sin(half), std::cos(half)};
}

void expectQuaternion(const Values& q, const glm::dvec4& want) {
  ASSERT_EQ(q.size(), 4u);
  for (int c = 0; c < 4; ++c) EXPECT_NEAR(q[size_t(c)], want[c], kDoubleRounding) << c;
}

TEST(KeyframeInterpolation, LinearRotationsSlerpAtConstantAngularSpeed) {
  const glm::dvec4 a = aboutZ(0), b = aboutZ(90);
  const KeyframeTrack t =
      track(Interpolation::Linear, 4, {0, 1}, {a.x, a.y, a.z, a.w, b.x, b.y, b.z, b.w}, true);
  expectQuaternion(sampleTrack(t, 0.5), aboutZ(45));
  // A quarter of the time, a quarter of the angle (a lerp would give 22.8 degrees here).
  expectQuaternion(sampleTrack(t, 0.25), aboutZ(22.5));
}

TEST(KeyframeInterpolation, SlerpTakesTheShorterArc) {
  // -q is the same rotation as q: from 0 to 90 degrees written as its negative, halfway is
  // 45 degrees (the long way round would pass through 225 degrees).
  const glm::dvec4 a = aboutZ(0), b = -aboutZ(90);
  const KeyframeTrack t =
      track(Interpolation::Linear, 4, {0, 1}, {a.x, a.y, a.z, a.w, b.x, b.y, b.z, b.w}, true);
  expectQuaternion(sampleTrack(t, 0.5), aboutZ(45));
  // 170 to -170 degrees (the quaternions' dot product is negative): 20 degrees apart the
  // short way, so halfway is 180.
  const glm::dvec4 q = slerpShortArc(aboutZ(170), aboutZ(-170), 0.5);
  const glm::dvec4 half_turn = aboutZ(180);
  EXPECT_NEAR(std::abs(glm::dot(q, half_turn)), 1.0, kDoubleRounding);
}

TEST(KeyframeInterpolation, SlerpOfEqualKeysIsThatKey) {
  // sin(angle) is 0 here: without the linear branch (kSlerpLinearAbove) this is 0 / 0.
  const glm::dvec4 q = aboutZ(30);
  for (double u : {0.0, 0.3, 1.0}) {
    const glm::dvec4 got = slerpShortArc(q, q, u);
    for (int c = 0; c < 4; ++c) EXPECT_NEAR(got[c], q[c], kDoubleRounding);
  }
  // Nearly equal keys, just above the threshold: the linear branch stays on the arc.
  const glm::dvec4 got = slerpShortArc(aboutZ(0), aboutZ(2), 0.5);
  for (int c = 0; c < 4; ++c) EXPECT_NEAR(got[c], aboutZ(1)[c], kDoubleRounding);
}

TEST(KeyframeInterpolation, SlerpNormalisesItsKeys) {
  const glm::dvec4 got = slerpShortArc(2.0 * aboutZ(0), 3.0 * aboutZ(90), 0.5);
  for (int c = 0; c < 4; ++c) EXPECT_NEAR(got[c], aboutZ(45)[c], kDoubleRounding);
}

TEST(KeyframeInterpolation, MorphWeightsInterpolateEachTarget) {
  // Two targets a key.
  const KeyframeTrack t = track(Interpolation::Linear, 2, {0, 1}, {0, 1, 1, 0});
  EXPECT_EQ(sampleTrack(t, 0.25), (Values{0.25, 0.75}));
}

}  // namespace
}  // namespace gridrt
