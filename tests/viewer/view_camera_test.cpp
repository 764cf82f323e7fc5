// The viewer's camera moves (view_camera.h): the amounts docs/viewer.md gives, measured
// here with the test's own geometry.
#include <gtest/gtest.h>

#include <cmath>

#include "camera_rays.h"
#include "view_camera.h"

namespace gridrt {
namespace {

// Angles recomputed in double from float positions a few ulps off: far below the degrees
// a move turns, far above float rounding.
constexpr double kAngleToleranceDegrees = 1e-3;
// Lengths and positions of order 1..10 computed in float through a few operations.
constexpr float kLengthTolerance = 1e-5f;

double degrees(double radians) { return radians * 180.0 / M_PI; }

double azimuth(const LookAt& v) {
  const glm::dvec3 u(v.eye - v.target);
  return degrees(std::atan2(u.x, u.z));
}
double elevation(const LookAt& v) {
  const glm::dvec3 u(v.eye - v.target);
  return degrees(std::asin(u.y / glm::length(u)));
}

const LookAt kView{{1.0f, 2.0f, 6.0f}, {0.5f, 0.5f, -0.5f}};

TEST(ViewCamera, OrbitTurnsTheEyeAboutTheTargetByTheAngleGiven) {
  const LookAt turned = orbited(kView, 30.0f, 0.0f);
  EXPECT_EQ(turned.target, kView.target);
  EXPECT_NEAR(azimuth(turned) - azimuth(kView), 30.0, kAngleToleranceDegrees);
  EXPECT_NEAR(elevation(turned), elevation(kView), kAngleToleranceDegrees);
  EXPECT_NEAR(glm::length(turned.eye - turned.target), glm::length(kView.eye - kView.target),
              kLengthTolerance);
  const LookAt raised = orbited(kView, 0.0f, 10.0f);
  EXPECT_NEAR(elevation(raised) - elevation(kView), 10.0, kAngleToleranceDegrees);
  EXPECT_NEAR(azimuth(raised), azimuth(kView), kAngleToleranceDegrees);
}

TEST(ViewCamera, OrbitStopsShortOfStraightUpAndDown) {
  EXPECT_NEAR(elevation(orbited(kView, 0.0f, 500.0f)), kMaxElevationDegrees,
              kAngleToleranceDegrees);
  EXPECT_NEAR(elevation(orbited(kView, 0.0f, -500.0f)), -kMaxElevationDegrees,
              kAngleToleranceDegrees);
}

TEST(ViewCamera, PanMovesEyeAndTargetTogetherAcrossTheView) {
  const float yfov = 0.7f;
  const int height = 200;
  const LookAt moved = panned(kView, 10.0f, -4.0f, yfov, height);
  const glm::vec3 shift = moved.eye - kView.eye;
  EXPECT_NEAR(glm::length(moved.target - kView.target - shift), 0.0f, kLengthTolerance);
  const glm::vec3 forward = glm::normalize(kView.target - kView.eye);
  EXPECT_NEAR(glm::dot(shift, forward), 0.0f, kLengthTolerance);  // in the image plane
  // A pixel at the target's distance: 2 d tan(yfov / 2) / height.
  const float pixel = 2.0f * glm::length(kView.target - kView.eye) * std::tan(yfov / 2) / height;
  EXPECT_NEAR(glm::length(shift), pixel * std::sqrt(116.0f), 1e-4f);
  // Dragging right moves the camera left (the scene follows the pointer).
  const glm::vec3 right = glm::normalize(glm::cross(forward, glm::vec3(0, 1, 0)));
  EXPECT_NEAR(glm::dot(shift, right), -10.0f * pixel, kLengthTolerance);
}

TEST(ViewCamera, ZoomStepsAShareOfTheWayToTheTarget) {
  const float d = glm::length(kView.eye - kView.target);
  const LookAt in = zoomed(kView, 1);
  EXPECT_EQ(in.target, kView.target);
  EXPECT_NEAR(glm::length(in.eye - in.target), d * (1.0f - kZoomPerNotch), kLengthTolerance);
  EXPECT_NEAR(azimuth(in), azimuth(kView), kAngleToleranceDegrees);
  const LookAt back = zoomed(in, -1);
  EXPECT_NEAR(glm::length(back.eye - kView.eye), 0.0f, kLengthTolerance);
}

TEST(ViewCamera, FlyMovesAlongTheViewRightAndUp) {
  const glm::vec3 forward = glm::normalize(kView.target - kView.eye);
  const LookAt ahead = flown(kView, {0, 0, 1}, 0.5f);
  EXPECT_NEAR(glm::length(ahead.eye - (kView.eye + 0.5f * forward)), 0.0f, kLengthTolerance);
  EXPECT_NEAR(glm::length(ahead.target - (kView.target + 0.5f * forward)), 0.0f,
              kLengthTolerance);
  const LookAt up = flown(kView, {0, 1, 0}, 0.5f);
  EXPECT_NEAR(glm::length(up.eye - kView.eye - glm::vec3(0, 0.5f, 0)), 0.0f, kLengthTolerance);
  const LookAt left = flown(kView, {-1, 0, 0}, 0.5f);
  const glm::vec3 right = glm::normalize(glm::cross(forward, glm::vec3(0, 1, 0)));
  EXPECT_NEAR(glm::dot(left.eye - kView.eye, right), -0.5f, kLengthTolerance);
}

TEST(ViewCamera, LookAtOfACameraLooksTheSameWay) {
  const Camera camera = lookAtCamera(kView.eye, kView.target, 0.7f);
  Bounds scene;
  scene.grow(glm::vec3(-1.0f));
  scene.grow(glm::vec3(1.0f));
  const LookAt view = lookAtOf(camera, scene);
  const Camera again = lookAtCamera(view.eye, view.target, 0.7f);
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 3; ++r) EXPECT_NEAR(again.world[c][r], camera.world[c][r], kLengthTolerance);
  // The target at the depth of the scene's centre along the line of sight.
  const glm::vec3 forward = glm::normalize(kView.target - kView.eye);
  EXPECT_NEAR(glm::length(view.target - view.eye), glm::dot(-kView.eye, forward), kLengthTolerance);
}

}  // namespace
}  // namespace gridrt
