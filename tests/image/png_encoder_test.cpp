// The PNG encoder gridrt writes its default output with (libpng, host/image/png_encoder.h)
// against the image module's (OpenImageIO's encoder, an independent implementation): the
// same pixels, decoded by the module, for every kind of value an image holds.
#include "png_encoder.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include "errors.h"
#include "image_module.h"
#include "image_output.h"
#include "test_support.h"

namespace gridrt {
namespace {

std::string freshDir(const std::string& name) { return test::freshDir("png_encoder_" + name); }

void writeBytes(const std::string& path, const std::vector<unsigned char>& bytes) {
  std::ofstream(path, std::ios::binary)
      .write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
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
    for (size_t p = 0; p < n; ++p) a[p] = p % 5 == 0 ? 0.0f : p % 5 == 1 ? 1.0f : unit(rng);
    a[3] = NAN;
    a[4] = 1.5f;
    image.channels.push_back(floatChannel("A", std::move(a)));
  }
  return image;
}

TEST(PngEncoder, PixelsEqualTheImageModulesOnEveryKindOfValue) {
  const std::string dir = freshDir("equal");
  for (bool alpha : {false, true})
    for (const auto& [width, height] : {std::pair{1, 1}, {7, 3}, {256, 129}}) {
      const LayeredImage image = testImage(width, height, alpha, uint32_t(width * 31 + alpha));
      writeBytes(dir + "/ours.png", encodePng(image));
      writeBytes(dir + "/module.png", imageCodec().encode(image, "png"));
      const ImageData ours = readImage(dir + "/ours.png");
      const ImageData module = readImage(dir + "/module.png");
      ASSERT_EQ(ours.width, width);
      ASSERT_EQ(ours.height, height);
      ASSERT_EQ(ours.channels, alpha ? 4 : 3);
      ASSERT_EQ(module.channels, ours.channels);
      size_t differ = 0;
      for (size_t k = 0; k < ours.pixels.size(); ++k) differ += ours.pixels[k] != module.pixels[k];
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
