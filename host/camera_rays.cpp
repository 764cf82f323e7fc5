#include "camera_rays.h"

#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <limits>

namespace gridrt {

Camera defaultCamera(const Bounds& bounds) {
  Camera c;
  c.name = "default";
  glm::vec3 center = bounds.center();
  float radius = 0.5f * glm::length(bounds.extent());
  if (!(radius > 0.0f)) radius = 1.0f;
  float distance = radius / std::sin(c.yfov * 0.5f);
  glm::vec3 eye = center + glm::vec3(0.0f, 0.0f, distance);
  c.world = glm::inverse(glm::lookAt(eye, center, glm::vec3(0, 1, 0)));
  return c;
}

Camera lookAtCamera(const glm::vec3& eye, const glm::vec3& target, float yfov) {
  Camera c;
  c.name = "look-at";
  c.yfov = yfov;
  glm::vec3 forward = glm::normalize(target - eye);
  glm::vec3 up = std::fabs(forward.y) > 0.999f ? glm::vec3(0, 0, 1) : glm::vec3(0, 1, 0);
  c.world = glm::inverse(glm::lookAt(eye, target, up));
  return c;
}

CameraRayGenerator::CameraRayGenerator(const Camera& camera, int width, int height)
    : camera_(camera),
      width_(float(width)),
      height_(float(height)),
      aspect_(camera.aspect > 0.0f ? camera.aspect : float(width) / float(height)),
      tan_half_(std::tan(camera.yfov * 0.5f)),
      origin_(camera.world[3]) {}

GrRay cameraRay(const Camera& camera, int width, int height, int i, int j, float sx, float sy) {
  return CameraRayGenerator(camera, width, height)(i, j, sx, sy);
}

void jitter(uint32_t pixel, uint32_t sample, float& sx, float& sy) {
  // PCG-style hash of (pixel, sample): cheap, deterministic, well spread.
  auto hash = [](uint32_t v) {
    v = v * 747796405u + 2891336453u;
    v = ((v >> ((v >> 28u) + 4u)) ^ v) * 277803737u;
    return (v >> 22u) ^ v;
  };
  uint32_t a = hash(pixel * 9781u + sample * 6271u + 1u);
  uint32_t b = hash(a ^ 0x9e3779b9u);
  sx = float(a >> 8) * (1.0f / 16777216.0f);
  sy = float(b >> 8) * (1.0f / 16777216.0f);
}

}  // namespace gridrt
