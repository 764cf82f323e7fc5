#include "default_lighting.h"

#include <cmath>

#include "whitted_shading.h"

namespace gridrt {

namespace {

// A directional light arriving from `from` (given in the camera's frame: right, up, towards
// the camera) with an irradiance of pi * exposure: a white Lambert surface facing it then
// has radiance exposure.
Light directionalLight(const Camera& camera, const glm::vec3& from, float exposure) {
  const glm::vec3 right(camera.world[0]), up(camera.world[1]), back(camera.world[2]);
  Light l;
  l.type = LightType::Directional;
  l.direction = -glm::normalize(from.x * right + from.y * up + from.z * back);
  l.intensity = kPi * exposure;
  return l;
}
}  // namespace

std::vector<Light> defaultLights(const Camera& camera) {
  return {directionalLight(camera, {-0.6f, 0.7f, 0.6f}, kKeyExposure),
          directionalLight(camera, {0.9f, 0.1f, 0.5f}, kFillExposure)};
}

}  // namespace gridrt
