// The film's radiance while a frame renders: three floats a pixel, in the layout of
// Film::rgb, so that the finished frame hands its buffer to the film instead of copying
// it (a 1280x960 frame's copy took ~4 % of a primary-ray frame's samples).
#pragma once
#include <glm/glm.hpp>
#include <vector>

namespace gridrt {

class PixelRadiance {
 public:
  // pixels values of zero, on all cores (the buffer keeps its memory from frame to frame).
  void clear(size_t pixels);
  glm::vec3 at(size_t p) const { return {rgb_[3 * p], rgb_[3 * p + 1], rgb_[3 * p + 2]}; }
  void add(size_t p, const glm::vec3& v) {
    rgb_[3 * p] += v.x;
    rgb_[3 * p + 1] += v.y;
    rgb_[3 * p + 2] += v.z;
  }
  void scale(size_t p, float k) {
    rgb_[3 * p] *= k;
    rgb_[3 * p + 1] *= k;
    rgb_[3 * p + 2] *= k;
  }
  // The values into `rgb` (3 a pixel); this takes rgb's old buffer, to be cleared before use.
  void moveInto(std::vector<float>& rgb) { rgb.swap(rgb_); }

 private:
  std::vector<float> rgb_;
};

}  // namespace gridrt
