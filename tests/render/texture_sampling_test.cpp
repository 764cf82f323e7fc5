// Texture lookups (texture_sampling.h) against values worked out by hand: wrapped texel
// indices, nearest and bilinear filtering at known coordinates, the choice of mip level.
#include "texture_sampling.h"

#include <gtest/gtest.h>

namespace gridrt {
namespace {

// A bilinear weight of 1/4 or 3/4 is exact in float; the sums of a few products of such
// weights and texel values in [0, 1] are within a few ulps of 1.
constexpr float kBlendTolerance = 1e-6f;

TEST(TextureSampling, WrappedTexelIndices) {
  EXPECT_EQ(wrapTexel(-1, 4, TextureWrap::Repeat), 3);
  EXPECT_EQ(wrapTexel(4, 4, TextureWrap::Repeat), 0);
  EXPECT_EQ(wrapTexel(-9, 4, TextureWrap::Repeat), 3);
  EXPECT_EQ(wrapTexel(-1, 4, TextureWrap::MirroredRepeat), 0);
  EXPECT_EQ(wrapTexel(4, 4, TextureWrap::MirroredRepeat), 3);
  EXPECT_EQ(wrapTexel(6, 4, TextureWrap::MirroredRepeat), 1);
  EXPECT_EQ(wrapTexel(8, 4, TextureWrap::MirroredRepeat), 0);
  EXPECT_EQ(wrapTexel(-5, 4, TextureWrap::MirroredRepeat), 3);
  EXPECT_EQ(wrapTexel(-2, 4, TextureWrap::ClampToEdge), 0);
  EXPECT_EQ(wrapTexel(7, 4, TextureWrap::ClampToEdge), 3);
  // Huge and non-finite coordinates stay inside the image.
  for (TextureWrap w : {TextureWrap::Repeat, TextureWrap::MirroredRepeat, TextureWrap::ClampToEdge})
    for (double i : {1e30, -1e30, double(NAN), double(INFINITY)}) {
      const int k = wrapTexel(i, 4, w);
      EXPECT_TRUE(k >= 0 && k < 4) << i;
    }
}

// A 2 x 2 level: black, red / green, blue.
TexelLevel twoByTwo() {
  TexelLevel level;
  level.width = level.height = 2;
  level.texels = {{0, 0, 0, 1}, {1, 0, 0, 1}, {0, 1, 0, 1}, {0, 0, 1, 1}};
  return level;
}

void expectNear(const glm::vec4& got, const glm::vec4& want) {
  for (int c = 0; c < 4; ++c) EXPECT_NEAR(got[c], want[c], kBlendTolerance) << "channel " << c;
}

TEST(TextureSampling, NearestReadsTheTexelContainingTheCoordinate) {
  const TexelLevel level = twoByTwo();
  Texture t;
  EXPECT_EQ(sampleLevel(level, t, {0.74f, 0.26f}, TextureFilter::Nearest), level.texels[1]);
  EXPECT_EQ(sampleLevel(level, t, {0.26f, 0.74f}, TextureFilter::Nearest), level.texels[2]);
  EXPECT_EQ(sampleLevel(level, t, {1.25f, 1.75f}, TextureFilter::Nearest), level.texels[2]);
}

TEST(TextureSampling, LinearBlendsBetweenTexelCentres) {
  const TexelLevel level = twoByTwo();
  Texture t;
  // At a texel's centre, the texel itself.
  expectNear(sampleLevel(level, t, {0.75f, 0.25f}, TextureFilter::Linear), level.texels[1]);
  // The image's centre: the mean of all four.
  expectNear(sampleLevel(level, t, {0.5f, 0.5f}, TextureFilter::Linear), {0.25f, 0.25f, 0.25f, 1});
  // At u = 0 the left and right columns meet when repeating; clamped, the left one alone.
  expectNear(sampleLevel(level, t, {0.0f, 0.25f}, TextureFilter::Linear), {0.5f, 0, 0, 1});
  t.wrap_s = TextureWrap::ClampToEdge;
  expectNear(sampleLevel(level, t, {0.0f, 0.25f}, TextureFilter::Linear), level.texels[0]);
  // A quarter of the way from the red centre towards the black one (u = 0.625).
  t.wrap_s = TextureWrap::Repeat;
  expectNear(sampleLevel(level, t, {0.625f, 0.25f}, TextureFilter::Linear), {0.75f, 0, 0, 1});
}

TexelImage threeLevels() {
  TexelImage image;
  for (int size = 4; size >= 1; size /= 2) {
    TexelLevel level;
    level.width = level.height = size;
    level.texels.assign(size_t(size * size), glm::vec4(float(size)));
    image.levels.push_back(level);
  }
  return image;  // levels of 4, 2 and 1 texels a side, each texel its level's side
}

TEST(TextureSampling, TheLevelOfDetailChoosesAndBlendsMipLevels) {
  const TexelImage image = threeLevels();
  Texture t;
  EXPECT_EQ(sampleTexture(image, t, {0.3f, 0.3f}, -2.0f), glm::vec4(4.0f));  // magnified
  EXPECT_EQ(sampleTexture(image, t, {0.3f, 0.3f}, 1.0f), glm::vec4(2.0f));
  expectNear(sampleTexture(image, t, {0.3f, 0.3f}, 0.5f), glm::vec4(3.0f));
  EXPECT_EQ(sampleTexture(image, t, {0.3f, 0.3f}, 9.0f), glm::vec4(1.0f));  // past the last
  t.mipmaps = false;
  EXPECT_EQ(sampleTexture(image, t, {0.3f, 0.3f}, 1.0f), glm::vec4(4.0f));
}

TEST(TextureSampling, MagnificationAndMinificationUseTheirOwnFilters) {
  TexelImage image;
  image.levels.push_back(twoByTwo());
  Texture t;
  t.mag_filter = TextureFilter::Nearest;
  t.min_filter = TextureFilter::Linear;
  t.mipmaps = false;
  const glm::vec2 centre(0.5f, 0.5f);
  EXPECT_EQ(sampleTexture(image, t, centre, 0.0f), image.levels[0].texels[3]);
  expectNear(sampleTexture(image, t, centre, 1.0f), {0.25f, 0.25f, 0.25f, 1});
}

}  // namespace
}  // namespace gridrt
