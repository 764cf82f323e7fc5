#include "layered_image.h"

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

}  // namespace gridrt
