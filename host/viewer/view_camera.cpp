#include "view_camera.h"

#include <algorithm>
#include <cmath>

namespace gridrt {

namespace {

constexpr float kRadiansPerDegree = 3.14159265358979f / 180.0f;
const glm::vec3 kWorldUp(0.0f, 1.0f, 0.0f);

glm::vec3 rightOf(const LookAt& view) {
  const glm::vec3 forward = glm::normalize(view.target - view.eye);
  const glm::vec3 right = glm::cross(forward, kWorldUp);
  const float length = glm::length(right);
  // Looking straight up or down: --look-at takes +Z as up there (lookAtCamera).
  return length > 0.0f ? right / length : glm::vec3(1.0f, 0.0f, 0.0f);
}

}  // namespace

LookAt lookAtOf(const Camera& camera, const Bounds& scene) {
  LookAt view;
  view.eye = glm::vec3(camera.world[3]);
  const glm::vec3 forward = glm::normalize(-glm::vec3(camera.world[2]));
  const glm::vec3 centre = 0.5f * (scene.lo + scene.hi);
  const float half_diagonal = scene.empty() ? 1.0f : 0.5f * glm::length(scene.hi - scene.lo);
  float distance = scene.empty() ? 1.0f : glm::dot(centre - view.eye, forward);
  if (!(distance > 0.0f)) distance = half_diagonal > 0.0f ? half_diagonal : 1.0f;
  view.target = view.eye + forward * distance;
  return view;
}

LookAt orbited(const LookAt& view, float yaw_degrees, float pitch_degrees) {
  const glm::vec3 offset = view.eye - view.target;
  const float r = glm::length(offset);
  const float elevation = std::asin(std::clamp(offset.y / r, -1.0f, 1.0f));
  const float azimuth = std::atan2(offset.x, offset.z);
  const float limit = kMaxElevationDegrees * kRadiansPerDegree;
  const float e = std::clamp(elevation + pitch_degrees * kRadiansPerDegree, -limit, limit);
  const float a = azimuth + yaw_degrees * kRadiansPerDegree;
  LookAt out = view;
  out.eye = view.target +
            r * glm::vec3(std::cos(e) * std::sin(a), std::sin(e), std::cos(e) * std::cos(a));
  return out;
}

LookAt panned(const LookAt& view, float dx, float dy, float yfov, int height) {
  const glm::vec3 forward = glm::normalize(view.target - view.eye);
  const glm::vec3 right = rightOf(view);
  const glm::vec3 up = glm::cross(right, forward);
  const float per_pixel =
      2.0f * glm::length(view.target - view.eye) * std::tan(0.5f * yfov) / float(std::max(1, height));
  const glm::vec3 shift = (-dx * right + dy * up) * per_pixel;
  return LookAt{view.eye + shift, view.target + shift};
}

LookAt zoomed(const LookAt& view, int notches) {
  const float factor = std::pow(1.0f - kZoomPerNotch, float(notches));
  return LookAt{view.target + (view.eye - view.target) * factor, view.target};
}

LookAt flown(const LookAt& view, const glm::vec3& amount, float step) {
  const glm::vec3 forward = glm::normalize(view.target - view.eye);
  const glm::vec3 shift =
      step * (amount.x * rightOf(view) + amount.y * kWorldUp + amount.z * forward);
  return LookAt{view.eye + shift, view.target + shift};
}

}  // namespace gridrt
