#include "pixel_blocks.h"

#include <algorithm>

namespace gridrt {

void pixelBlockOrder(int width, int height, std::vector<int>& order) {
  order.clear();
  order.reserve(size_t(std::max(width, 0)) * size_t(std::max(height, 0)));
  for (int by = 0; by < height; by += kPixelBlockEdge)
    for (int bx = 0; bx < width; bx += kPixelBlockEdge)
      for (int y = by; y < std::min(height, by + kPixelBlockEdge); ++y)
        for (int x = bx; x < std::min(width, bx + kPixelBlockEdge); ++x)
          order.push_back(y * width + x);
}

}  // namespace gridrt
