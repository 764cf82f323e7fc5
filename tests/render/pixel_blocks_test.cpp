// The shading order of the primary generation (host/render/pixel_blocks.h): every pixel once,
// 16 consecutive entries one 4x4 block where the window allows it.
#include "pixel_blocks.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

namespace {

using gridrt::kPixelBlockEdge;
using gridrt::pixelBlockOrder;

TEST(PixelBlocks, EveryPixelOfTheWindowOnce) {
  for (auto [w, h] : {std::pair{640, 480}, {1, 1}, {10, 7}, {3, 13}, {17, 4}}) {
    std::vector<int> order;
    pixelBlockOrder(w, h, order);
    ASSERT_EQ(order.size(), size_t(w) * h) << w << "x" << h;
    std::vector<int> sorted = order;
    std::sort(sorted.begin(), sorted.end());
    for (int k = 0; k < w * h; ++k) ASSERT_EQ(sorted[k], k) << w << "x" << h;
  }
}

TEST(PixelBlocks, SixteenConsecutivePixelsAreOneSquareBlock) {
  const int w = 64, h = 32;
  std::vector<int> order;
  pixelBlockOrder(w, h, order);
  for (size_t first = 0; first < order.size(); first += 16) {
    int x0 = w, y0 = h, x1 = -1, y1 = -1;
    for (size_t k = first; k < first + 16; ++k) {
      x0 = std::min(x0, order[k] % w);
      x1 = std::max(x1, order[k] % w);
      y0 = std::min(y0, order[k] / w);
      y1 = std::max(y1, order[k] / w);
    }
    EXPECT_EQ(x1 - x0 + 1, kPixelBlockEdge) << "packet at " << first;
    EXPECT_EQ(y1 - y0 + 1, kPixelBlockEdge) << "packet at " << first;
    EXPECT_EQ(x0 % kPixelBlockEdge, 0);
    EXPECT_EQ(y0 % kPixelBlockEdge, 0);
  }
}

TEST(PixelBlocks, EdgeBlocksAreClippedToTheWindow) {
  // 6 x 5: blocks 4x4, 2x4, 4x1, 2x1, in that order.
  std::vector<int> order;
  pixelBlockOrder(6, 5, order);
  const std::vector<int> expected = {0,  1, 2, 3,  6,  7,  8,  9,  12, 13, 14, 15, 18, 19, 20,
                                     21, 4, 5, 10, 11, 16, 17, 22, 23, 24, 25, 26, 27, 28, 29};
  EXPECT_EQ(order, expected);
}

}  // namespace
