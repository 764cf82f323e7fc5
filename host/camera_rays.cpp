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

GrRay CameraRayGenerator::operator()(int i, int j, float sx, float sy) const {
  float x = 2.0f * (float(i) + sx) / width_ - 1.0f;
  float y = 1.0f - 2.0f * (float(j) + sy) / height_;
  glm::vec3 origin, direction;
  if (camera_.orthographic) {
    // ymag is the half height; the image aspect sets the half width.
    glm::vec4 o = camera_.world * glm::vec4(x * camera_.ymag * aspect_, y * camera_.ymag, 0.0f, 1.0f);
    origin = glm::vec3(o);
    direction = glm::vec3(camera_.world * glm::vec4(0.0f, 0.0f, -1.0f, 0.0f));
  } else {
    glm::vec3 d(x * tan_half_ * aspect_, y * tan_half_, -1.0f);
    origin = origin_;
    direction = glm::vec3(camera_.world * glm::vec4(glm::normalize(d), 0.0f));
  }
  direction = glm::normalize(direction);
  return GrRay{origin.x, origin.y, origin.z, 0.0f, direction.x, direction.y, direction.z,
               std::numeric_limits<float>::infinity()};
}

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
