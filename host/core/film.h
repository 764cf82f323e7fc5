// The rendered image in memory: linear RGB floats and coverage, before any encoding for a
// file.
#pragma once
#include <glm/glm.hpp>
#include <vector>

namespace gridrt {

// Linear RGB float image, row-major, row 0 = top.
struct Film {
  int width = 0, height = 0;
  std::vector<float> rgb;  // 3 * width * height: the colour, the background where rays missed
  // width * height: the share of each pixel's camera samples that hit something (the image's
  // alpha); empty: the image has no alpha channel.
  std::vector<float> alpha;
  glm::vec3 background{0.0f};  // the colour rays that missed were given
};

}  // namespace gridrt
