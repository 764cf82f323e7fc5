// The rendered image in memory: linear RGB floats, before any encoding for a file.
#pragma once
#include <vector>

namespace gridrt {

// Linear RGB float image, row-major, row 0 = top.
struct Film {
  int width = 0, height = 0;
  std::vector<float> rgb;  // 3 * width * height
};

}  // namespace gridrt
