// What an intersector needs to know about a batch of primary rays from a pinhole camera:
// ray k is the centre ray of pixel k of `window` (row-major), made by CameraRayGenerator.
// The GridRT intersector uses it to bin rays by PE through each voxel's screen footprint.
#pragma once
#include <glm/glm.hpp>

#include "pixel_window.h"
#include "scene.h"

namespace gridrt {

struct PinholeView {
  glm::mat4 world_to_camera{1.0f};
  // The inverse of the camera's float world matrix in double: the projection the camera
  // bundles' outlines use (camera_bundles.cpp), free of the float inverse's cancellation
  // (a box far from the world origin seen from nearby).
  glm::dmat4 exact_world_to_camera{1.0};
  float tan_half = 0.0f;      // tan(yfov / 2)
  float aspect = 1.0f;        // width / height of the image plane
  int width = 0, height = 0;  // the full image
  PixelWindow window;         // the pixels of this batch

  static PinholeView of(const Camera& camera, int width, int height, PixelWindow window);
};

}  // namespace gridrt
