// Primary rays with the pinned camera convention (docs/camera.md): pixel
// (i, j), i the column from the left, j the row from the top, camera-space direction
// normalize(((2(i+0.5)/W - 1) tan(yfov/2) W/H, (1 - 2(j+0.5)/H) tan(yfov/2), -1)), to
// world by the camera's world matrix; origin the camera's world position.
#pragma once
#include <cstdint>
#include <glm/glm.hpp>
#include <limits>
#include <vector>

#include "bounds.h"
#include "gridrt_types.h"
#include "pixel_window.h"
#include "scene.h"

namespace gridrt {

// A camera that frames `bounds` from a three-quarter view (from the front, turned
// kDefaultAzimuth to the right and raised kDefaultElevation), so that the box's bounding
// sphere fills the vertical field of view.
constexpr float kDefaultAzimuth = 0.6108652f;    // 35 degrees about +Y, from +Z towards +X
constexpr float kDefaultElevation = 0.4363323f;  // 25 degrees above the horizon
Camera defaultCamera(const Bounds& bounds);

// Eye-to-target camera override (gridrt --look-at), +Y up.
Camera lookAtCamera(const glm::vec3& eye, const glm::vec3& target, float yfov);

// Primary rays of one camera and image size, with the per-image constants computed once.
class CameraRayGenerator {
 public:
  CameraRayGenerator(const Camera& camera, int width, int height);
  // The ray through pixel (i, j) at sub-pixel offset (sx, sy) in [0,1) (0.5,0.5 = centre).
  GrRay operator()(int i, int j, float sx, float sy) const;
  // The centre rays of pixels [i0, i1) of row j into out[0 .. i1 - i0): the same rays as
  // operator()(i, j, 0.5, 0.5), bit for bit, written so that the compiler vectorises them.
  // With dx, dy, dz (all three or none), their directions also into dx[0 .. i1 - i0) etc.
  void centreRow(int j, int i0, int i1, GrRay* out, float* dx = nullptr, float* dy = nullptr,
                 float* dz = nullptr) const;
  // The centre rays of every pixel of `window`, row-major, into out[0 .. width * height),
  // row by row on all cores.
  void centreWindow(const PixelWindow& window, GrRay* out) const;
  // True for a pinhole camera: every ray starts at its eye, over [0, inf).
  bool pinhole() const { return !camera_.orthographic; }

 private:
  const Camera& camera_;
  float width_, height_, aspect_, tan_half_;
  glm::vec3 origin_;
};

// Inline: the renderer calls it once per pixel.
inline GrRay CameraRayGenerator::operator()(int i, int j, float sx, float sy) const {
  float x = 2.0f * (float(i) + sx) / width_ - 1.0f;
  float y = 1.0f - 2.0f * (float(j) + sy) / height_;
  glm::vec3 origin, direction;
  if (camera_.orthographic) {
    // ymag is the half height; the image aspect sets the half width.
    glm::vec4 o =
        camera_.world * glm::vec4(x * camera_.ymag * aspect_, y * camera_.ymag, 0.0f, 1.0f);
    origin = glm::vec3(o);
    direction = glm::vec3(camera_.world * glm::vec4(0.0f, 0.0f, -1.0f, 0.0f));
  } else {
    glm::vec3 d(x * tan_half_ * aspect_, y * tan_half_, -1.0f);
    origin = origin_;
    direction = glm::vec3(camera_.world * glm::vec4(glm::normalize(d), 0.0f));
  }
  direction = glm::normalize(direction);
  return GrRay{origin.x,    origin.y,    origin.z,    0.0f,
               direction.x, direction.y, direction.z, std::numeric_limits<float>::infinity()};
}

// A box holding the origin of every primary ray of the camera: its eye, or for an
// orthographic camera its image rectangle (the grid's margin scales with it,
// GridSettings::ray_origins).
Bounds primaryRayOrigins(const Camera& camera, int width, int height);

// One ray, for callers that need a few (same result as CameraRayGenerator).
GrRay cameraRay(const Camera& camera, int width, int height, int i, int j, float sx, float sy);

// A deterministic sub-pixel offset for sample `s` of pixel `pixel` (spp > 1 jitter).
void jitter(uint32_t pixel, uint32_t sample, float& sx, float& sy);

}  // namespace gridrt
