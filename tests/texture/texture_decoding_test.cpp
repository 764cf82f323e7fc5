// Decoding a scene's images (texture_decoding.h): PNG bytes made here through OpenImageIO
// become linear texels for colour lookups (sRGB undone, by the sRGB specification's
// formula computed here) and the stored values for data lookups; what cannot be decoded
// is a warning, and unused images are not decoded.
#include "texture_decoding.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "png_encoding.h"

namespace gridrt {
namespace {

// OpenImageIO's float sRGB curve against the double formula: within a few float ulps.
constexpr double kSrgbTolerance = 1e-6;

// A scene of one image (`bytes`) that material 0 reads as base colour (colour) and as
// metallic-roughness (data), each as asked.
Scene sceneWithImage(std::vector<unsigned char> bytes, bool colour, bool data) {
  Scene scene;
  SceneImage image;
  image.name = "image 0";
  image.mime_type = "image/png";
  image.encoded = std::move(bytes);
  scene.images.push_back(image);
  Texture texture;
  texture.image = 0;
  scene.textures.push_back(texture);
  Material m;
  if (colour) m.base_color_texture.texture = 0;
  if (data) m.metallic_roughness_texture.texture = 0;
  scene.materials.push_back(m);
  return scene;
}

TEST(TextureDecoding, ColourTexelsAreLinearDataTexelsAsStored) {
  const std::vector<uint8_t> codes = {0, 10, 128, 255, 64, 200};
  Scene scene = sceneWithImage(test::encodePng(2, 1, 3, codes), true, true);
  decodeTextures(scene);
  ASSERT_TRUE(scene.warnings.empty()) << scene.warnings[0];
  const SceneImage& image = scene.images[0];
  ASSERT_FALSE(image.colour.empty());
  ASSERT_FALSE(image.data.empty());
  const TexelLevel& colour = image.colour.levels[0];
  const TexelLevel& data = image.data.levels[0];
  ASSERT_EQ(colour.width, 2);
  ASSERT_EQ(colour.height, 1);
  for (int t = 0; t < 2; ++t)
    for (int c = 0; c < 3; ++c) {
      const double stored = codes[size_t(3 * t + c)] / 255.0;
      EXPECT_NEAR(colour.texels[size_t(t)][c], test::srgbDecoded(stored), kSrgbTolerance);
      EXPECT_NEAR(data.texels[size_t(t)][c], stored, kSrgbTolerance);
    }
  EXPECT_EQ(colour.texels[0].a, 1.0f);        // no alpha channel: opaque
  EXPECT_EQ(image.colour.levels.size(), 2u);  // 2x1, then 1x1
}

TEST(TextureDecoding, GreyImagesSpreadToRgbAndKeepTheirAlpha) {
  Scene scene = sceneWithImage(test::encodePng(1, 1, 2, {51, 102}), false, true);
  decodeTextures(scene);
  const glm::vec4 texel = scene.images[0].data.levels[0].texels[0];
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(texel[c], 0.2, kSrgbTolerance);
  EXPECT_NEAR(texel.a, 0.4, kSrgbTolerance);
  EXPECT_TRUE(scene.images[0].colour.empty());  // never read as colour
}

TEST(TextureDecoding, AnImageThatCannotBeDecodedIsAWarningAndStaysEmpty) {
  Scene scene =
      sceneWithImage({'n', 'o', 't', ' ', 'a', 'n', ' ', 'i', 'm', 'a', 'g', 'e'}, true, false);
  decodeTextures(scene);
  ASSERT_EQ(scene.warnings.size(), 1u);
  EXPECT_NE(scene.warnings[0].find("image 0: cannot decode"), std::string::npos)
      << scene.warnings[0];
  EXPECT_TRUE(scene.images[0].colour.empty());
}

TEST(TextureDecoding, ImagesNoMaterialReadsAreNotDecoded) {
  Scene scene = sceneWithImage({'x'}, false, false);
  decodeTextures(scene);
  EXPECT_TRUE(scene.warnings.empty());
  EXPECT_TRUE(scene.images[0].colour.empty() && scene.images[0].data.empty());
}

}  // namespace
}  // namespace gridrt
