// Primary rays with the pinned camera convention (README "Camera convention"): pixel
// (i, j), i the column from the left, j the row from the top, camera-space direction
// normalize(((2(i+0.5)/W - 1) tan(yfov/2) W/H, (1 - 2(j+0.5)/H) tan(yfov/2), -1)), to
// world by the camera's world matrix; origin the camera's world position.
#pragma once
#include <cstdint>
#include <vector>

#include "bounds.h"
#include "gridrt_types.h"
#include "scene.h"

namespace gridrt {

// A camera that frames `bounds`: looking down -Z from in front of the box, so the box's
// bounding sphere fills the vertical field of view.
Camera defaultCamera(const Bounds& bounds);

// Eye-to-target camera override (gridrt --look-at), +Y up.
Camera lookAtCamera(const glm::vec3& eye, const glm::vec3& target, float yfov);

// Primary rays of one camera and image size, with the per-image constants computed once.
class CameraRayGenerator {
 public:
  CameraRayGenerator(const Camera& camera, int width, int height);
  // The ray through pixel (i, j) at sub-pixel offset (sx, sy) in [0,1) (0.5,0.5 = centre).
  GrRay operator()(int i, int j, float sx, float sy) const;

 private:
  const Camera& camera_;
  float width_, height_, aspect_, tan_half_;
  glm::vec3 origin_;
};

// One ray, for callers that need a few (same result as CameraRayGenerator).
GrRay cameraRay(const Camera& camera, int width, int height, int i, int j, float sx, float sy);

// A deterministic sub-pixel offset for sample `s` of pixel `pixel` (spp > 1 jitter).
void jitter(uint32_t pixel, uint32_t sample, float& sx, float& sy);

}  // namespace gridrt
