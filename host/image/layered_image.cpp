#include "layered_image.h"

#include <string>

#include "errors.h"

namespace gridrt {

ImageChannel floatChannel(const std::string& name, const std::vector<float>& interleaved, int count,
                          int c) {
  ImageChannel channel{name, SampleType::Float, {}, {}};
  const size_t pixels = interleaved.size() / size_t(count);
  channel.floats.resize(pixels);
  for (size_t p = 0; p < pixels; ++p) channel.floats[p] = interleaved[p * count + c];
  return channel;
}

ImageChannel idChannel(const std::string& name, const std::vector<int32_t>& ids) {
  ImageChannel channel{name, SampleType::UInt, {}, {}};
  channel.uints.assign(ids.begin(), ids.end());  // two's complement: -1 -> 2^32 - 1
  return channel;
}

int channelIndex(const LayeredImage& image, const std::string& name) {
  for (size_t c = 0; c < image.channels.size(); ++c)
    if (image.channels[c].name == name) return int(c);
  return -1;
}

namespace {

[[noreturn]] void fail(const std::string& reason) { throw RenderError(reason); }

}  // namespace

void checkImage(const LayeredImage& image) {
  if (image.width <= 0 || image.height <= 0 || image.channels.empty())
    fail("invalid image size " + std::to_string(image.width) + "x" + std::to_string(image.height) +
         " with " + std::to_string(image.channels.size()) + " channels");
  const size_t expected = size_t(image.width) * size_t(image.height);
  for (const ImageChannel& c : image.channels)
    if (c.size() != expected)
      fail("image is " + std::to_string(image.width) + "x" + std::to_string(image.height) +
           " but channel '" + c.name + "' has " + std::to_string(c.size()) + " values (expected " +
           std::to_string(expected) + ")");
}

const ImageChannel& colourChannel(const LayeredImage& image, const char* name) {
  const int c = channelIndex(image, name);
  if (c < 0 || image.channels[c].type != SampleType::Float)
    fail("an 8-bit image needs float channels R, G and B");
  return image.channels[c];
}

}  // namespace gridrt
