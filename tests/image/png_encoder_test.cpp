// The 8-bit codes of PNG and JPEG (host/image/eight_bit_image.h) and the PNG encoder
// (libpng, host/image/png_encoder.h): a PNG decoded by libpng holds, for every kind of
// value an image holds, the codes OpenImageIO makes of it (its linear_to_sRGB and its
// float-to-8-bit conversion, an independent implementation), unassociated from alpha.
#include "png_encoder.h"

#include <OpenImageIO/color.h>
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>
#include <png.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include "eight_bit_image.h"
#include "errors.h"

namespace gridrt {
namespace {

// A PNG's pixels decoded by libpng, as stored: 8-bit R, G, B (and A).
std::vector<unsigned char> decodePng(const std::vector<unsigned char>& bytes, int& channels) {
  png_image png{};
  png.version = PNG_IMAGE_VERSION;
  EXPECT_TRUE(png_image_begin_read_from_memory(&png, bytes.data(), bytes.size())) << png.message;
  channels = PNG_IMAGE_PIXEL_CHANNELS(png.format);
  png.format = channels == 4 ? PNG_FORMAT_RGBA : PNG_FORMAT_RGB;
  channels = PNG_IMAGE_PIXEL_CHANNELS(png.format);
  std::vector<unsigned char> pixels(PNG_IMAGE_SIZE(png));
  EXPECT_TRUE(png_image_finish_read(&png, nullptr, pixels.data(), 0, nullptr)) << png.message;
  return pixels;
}

// OpenImageIO's code for a value in [0, 1]: its own conversion of floats to 8 bits.
unsigned char oiioCode(float unit) {
  unsigned char out = 0;
  OIIO::convert_pixel_values(OIIO::TypeDesc::FLOAT, &unit, OIIO::TypeDesc::UINT8, &out, 1);
  return out;
}

// What a pixel's channel c should hold: coverage clamped (NaN as 0), the colour divided by
// it or the background, clamped (NaN as 0), sRGB-encoded by OpenImageIO.
unsigned char expectedCode(const LayeredImage& image, size_t p, int c) {
  const int a = channelIndex(image, "A");
  float coverage = 1.0f;
  if (a >= 0) {
    const float value = image.channels[a].floats[p];
    coverage = std::isnan(value) ? 0.0f : std::clamp(value, 0.0f, 1.0f);
    if (c == 3) return oiioCode(coverage);
  }
  float v = image.channels[c].floats[p];
  if (coverage == 0.0f)
    v = image.background[c];
  else if (coverage < 1.0f)
    v /= coverage;
  return oiioCode(OIIO::linear_to_sRGB(std::isnan(v) ? 0.0f : std::clamp(v, 0.0f, 1.0f)));
}

ImageChannel floatChannel(const std::string& name, std::vector<float> values) {
  ImageChannel c;
  c.name = name;
  c.floats = std::move(values);
  return c;
}

// Values across every code and the cases at its ends: the darks densely (sRGB's linear
// segment and its knee), out of range, NaN, infinities; alpha 0, 1 and between.
LayeredImage testImage(int width, int height, bool alpha, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  const float specials[] = {0.0f,     -0.0f,    1.0f,      0.0031308f, 0.0031309f, -1.0f,
                            2.0f,     NAN,      INFINITY,  -INFINITY,  1e-30f,     0.5f,
                            0.99999f, 1.00001f, 0.214041f, 0.0404482f};
  const size_t n = size_t(width) * height;
  LayeredImage image;
  image.width = width;
  image.height = height;
  image.background = {0.25f, 0.5f, 1.0f};
  for (const char* name : {"R", "G", "B"}) {
    std::vector<float> v(n);
    for (size_t p = 0; p < n; ++p) {
      const float u = unit(rng);
      v[p] = p % 7 == 0 ? specials[(p / 7) % std::size(specials)] : p % 2 ? u : u * u * u;
    }
    image.channels.push_back(floatChannel(name, std::move(v)));
  }
  if (alpha) {
    std::vector<float> a(n);
    const float specials_a[] = {0.0f, 1.0f, NAN, 1.5f, -0.5f};  // then values between
    for (size_t p = 0; p < n; ++p)
      a[p] = p % 7 < std::size(specials_a) ? specials_a[p % 7] : unit(rng);
    image.channels.push_back(floatChannel("A", std::move(a)));
  }
  return image;
}

TEST(PngEncoder, HoldsOpenImageIOsCodesOfEveryKindOfValue) {
  for (bool alpha : {false, true})
    for (const auto& [width, height] : {std::pair{1, 1}, {7, 3}, {256, 129}}) {
      const LayeredImage image = testImage(width, height, alpha, uint32_t(width * 31 + alpha));
      int channels = 0;
      const std::vector<unsigned char> pixels = decodePng(encodePng(image), channels);
      ASSERT_EQ(channels, alpha ? 4 : 3);
      ASSERT_EQ(pixels.size(), size_t(width) * height * channels);
      size_t differ = 0;
      for (size_t p = 0; p < size_t(width) * height; ++p)
        for (int c = 0; c < channels; ++c)
          differ += pixels[p * channels + c] != expectedCode(image, p, c);
      EXPECT_EQ(differ, 0u) << width << "x" << height << (alpha ? " with alpha" : "");
    }
}

TEST(PngEncoder, EveryCodeIsReachedAndRoundedToTheNearest) {
  // The codes' midpoints decoded: just below one rounds down, just above rounds up.
  for (int code = 0; code < 255; ++code) {
    const double mid = (code + 0.5) / 255.0;  // in the encoded (sRGB) scale
    const double linear =
        mid <= 0.04045 ? mid / 12.92 : std::pow((mid + 0.055) / 1.055, 2.4);  // its inverse
    EXPECT_EQ(int(linearToSrgb8(float(linear * (1 - 1e-4)))), code) << code;
    EXPECT_EQ(int(linearToSrgb8(float(linear * (1 + 1e-4)))), code + 1) << code;
  }
  EXPECT_EQ(int(linearToSrgb8(0.0f)), 0);
  EXPECT_EQ(int(linearToSrgb8(1.0f)), 255);
}

TEST(PngEncoder, RefusesWhatAnEightBitFileCannotHold) {
  EXPECT_THROW(eightBitImage(testImage(4, 4, true, 4), "jpg"), RenderError);  // alpha
  LayeredImage window = testImage(4, 4, false, 1);
  window.full_width = window.full_height = 8;
  EXPECT_THROW(encodePng(window), RenderError);
  LayeredImage no_blue = testImage(4, 4, false, 2);
  no_blue.channels.pop_back();
  EXPECT_THROW(encodePng(no_blue), RenderError);
  LayeredImage short_channel = testImage(4, 4, false, 3);
  short_channel.channels[1].floats.pop_back();
  EXPECT_THROW(encodePng(short_channel), RenderError);
  LayeredImage empty;
  EXPECT_THROW(encodePng(empty), RenderError);
}

}  // namespace
}  // namespace gridrt
