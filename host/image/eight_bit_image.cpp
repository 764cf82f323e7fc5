#include "eight_bit_image.h"

#include <algorithm>
#include <cmath>

#include "errors.h"
#include "parallel_loops.h"

namespace gridrt {

namespace {

[[noreturn]] void fail(const std::string& reason) { throw RenderError(reason); }

unsigned char code(float unit) { return static_cast<unsigned char>(unit * 255.0f + 0.5f); }

}  // namespace

unsigned char linearToSrgb8(float linear) {
  const float v =
      linear <= 0.0031308f ? 12.92f * linear : 1.055f * std::pow(linear, 1.0f / 2.4f) - 0.055f;
  return code(std::clamp(v, 0.0f, 1.0f));
}

EightBitImage eightBitImage(const LayeredImage& image, const std::string& format) {
  if (image.x != 0 || image.y != 0 ||
      (image.full_width && (image.full_width != image.width || image.full_height != image.height)))
    fail("an 8-bit image cannot hold a window of a larger one (use .exr)");
  const ImageChannel* rgb[3] = {&colourChannel(image, "R"), &colourChannel(image, "G"),
                                &colourChannel(image, "B")};
  const int a = channelIndex(image, "A");
  if (a >= 0 && format != "png") fail(format + " holds no alpha channel (use .png, .exr or .tif)");
  const bool alpha = a >= 0;
  if (alpha && image.channels[a].type != SampleType::Float) fail("alpha must be a float channel");
  EightBitImage out;
  out.channels = alpha ? 4 : 3;
  const int nc = out.channels;
  const size_t pixels = size_t(image.width) * size_t(image.height);
  out.codes.resize(pixels * nc);
  parallelFor(size_t(0), pixels, [&](size_t p) {
    float coverage = 1.0f;
    if (alpha) {
      const float value = image.channels[a].floats[p];
      coverage = std::isnan(value) ? 0.0f : std::clamp(value, 0.0f, 1.0f);
      out.codes[p * 4 + 3] = code(coverage);
    }
    for (int c = 0; c < 3; ++c) {
      float v = rgb[c]->floats[p];
      if (coverage == 0.0f)
        v = image.background[c];
      else if (coverage < 1.0f)
        v /= coverage;
      out.codes[p * nc + c] = linearToSrgb8(std::isnan(v) ? 0.0f : std::clamp(v, 0.0f, 1.0f));
    }
  });
  return out;
}

}  // namespace gridrt
