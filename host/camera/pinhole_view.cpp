#include "pinhole_view.h"

#include <cmath>

namespace gridrt {

PinholeView PinholeView::of(const Camera& camera, int width, int height, PixelWindow window) {
  PinholeView v;
  v.world_to_camera = glm::inverse(camera.world);
  v.exact_world_to_camera = glm::inverse(glm::dmat4(camera.world));
  v.tan_half = std::tan(camera.yfov * 0.5f);
  v.aspect = float(width) / float(height);
  v.width = width;
  v.height = height;
  v.window = window.orWholeImage(width, height);
  return v;
}

}  // namespace gridrt
