#include "png_encoder.h"

#include <png.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "errors.h"
#include "parallel_loops.h"

namespace gridrt {

namespace {

[[noreturn]] void fail(const std::string& reason) { throw RenderError(reason); }

const ImageChannel& colourChannel(const LayeredImage& image, const char* name) {
  const int c = channelIndex(image, name);
  if (c < 0 || image.channels[c].type != SampleType::Float)
    fail("an 8-bit image needs float channels R, G and B");
  return image.channels[c];
}

}  // namespace

unsigned char linearToSrgb8(float linear) {
  const float v =
      linear <= 0.0031308f ? 12.92f * linear : 1.055f * std::pow(linear, 1.0f / 2.4f) - 0.055f;
  return static_cast<unsigned char>(std::clamp(v, 0.0f, 1.0f) * 255.0f + 0.5f);
}

std::vector<unsigned char> encodePng(const LayeredImage& image) {
  if (image.width <= 0 || image.height <= 0)
    fail("invalid image size " + std::to_string(image.width) + "x" + std::to_string(image.height));
  if (image.x != 0 || image.y != 0 ||
      (image.full_width && (image.full_width != image.width || image.full_height != image.height)))
    fail("an 8-bit image cannot hold a window of a larger one (use .exr)");
  const ImageChannel* rgb[3] = {&colourChannel(image, "R"), &colourChannel(image, "G"),
                                &colourChannel(image, "B")};
  const int a = channelIndex(image, "A");
  const bool alpha = a >= 0;
  if (alpha && image.channels[a].type != SampleType::Float) fail("alpha must be a float channel");
  const size_t pixels = size_t(image.width) * size_t(image.height);
  for (const ImageChannel& c : image.channels)
    if (c.size() != pixels)
      fail("image is " + std::to_string(image.width) + "x" + std::to_string(image.height) +
           " but channel '" + c.name + "' has " + std::to_string(c.size()) + " values");
  const int nc = alpha ? 4 : 3;
  std::vector<unsigned char> encoded(pixels * nc);
  parallelFor(size_t(0), pixels, [&](size_t p) {
    float coverage = 1.0f;
    if (alpha) {
      const float value = image.channels[a].floats[p];
      coverage = std::isnan(value) ? 0.0f : std::clamp(value, 0.0f, 1.0f);
      encoded[p * 4 + 3] = static_cast<unsigned char>(coverage * 255.0f + 0.5f);
    }
    for (int c = 0; c < 3; ++c) {
      float v = rgb[c]->floats[p];
      if (coverage == 0.0f)
        v = image.background[c];
      else if (coverage < 1.0f)
        v /= coverage;
      encoded[p * nc + c] = linearToSrgb8(std::isnan(v) ? 0.0f : std::clamp(v, 0.0f, 1.0f));
    }
  });

  // libpng's simplified writer: 8-bit values are written as they are, with an sRGB chunk.
  png_image png{};
  png.version = PNG_IMAGE_VERSION;
  png.width = png_uint_32(image.width);
  png.height = png_uint_32(image.height);
  png.format = alpha ? PNG_FORMAT_RGBA : PNG_FORMAT_RGB;
  png_alloc_size_t size = PNG_IMAGE_PNG_SIZE_MAX(png);  // room for any encoding, one pass
  std::vector<unsigned char> bytes(size);
  if (!png_image_write_to_memory(&png, bytes.data(), &size, 0, encoded.data(), 0, nullptr))
    fail(std::string("PNG encoding failed: ") + png.message);
  bytes.resize(size);
  return bytes;
}

}  // namespace gridrt
