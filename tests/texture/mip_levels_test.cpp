// Mip levels (mip_levels.h): sizes halved down to 1 x 1, each texel the mean of the
// texels it covers, odd sizes' last row and column included.
#include "mip_levels.h"

#include <gtest/gtest.h>

namespace gridrt {
namespace {

// Means of up to nine texel values in [0, 16]: a few ulps of 16.
constexpr float kMeanTolerance = 1e-5f;

TexelLevel counting(int width, int height) {
  TexelLevel level;
  level.width = width;
  level.height = height;
  for (int i = 0; i < width * height; ++i) level.texels.push_back(glm::vec4(float(i)));
  return level;
}

TEST(MipLevels, HalveDownToOneTexel) {
  const TexelImage image = withMipLevels(counting(8, 2));
  ASSERT_EQ(image.levels.size(), 4u);
  const int sizes[][2] = {{8, 2}, {4, 1}, {2, 1}, {1, 1}};
  for (size_t l = 0; l < 4; ++l) {
    EXPECT_EQ(image.levels[l].width, sizes[l][0]);
    EXPECT_EQ(image.levels[l].height, sizes[l][1]);
  }
  // Level 1 texel 0: texels 0, 1 (row 0) and 8, 9 (row 1).
  EXPECT_NEAR(image.levels[1].texels[0].x, (0 + 1 + 8 + 9) / 4.0f, kMeanTolerance);
  // The last level: the mean of all 16.
  EXPECT_NEAR(image.levels[3].texels[0].x, 7.5f, kMeanTolerance);
}

TEST(MipLevels, OddSizesKeepTheirLastRowAndColumn) {
  const TexelImage image = withMipLevels(counting(3, 3));
  ASSERT_EQ(image.levels.size(), 2u);
  EXPECT_EQ(image.levels[1].width, 1);
  EXPECT_NEAR(image.levels[1].texels[0].x, 4.0f, kMeanTolerance);  // the mean of 0..8
}

}  // namespace
}  // namespace gridrt
