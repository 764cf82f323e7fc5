// An image as its file holds it: named channels of 32-bit floats or 32-bit unsigned
// integers, and where its pixels lie. One such image is what the image module encodes
// (an 8-bit picture, a float EXR, a multi-layer EXR of the image and its AOVs) and what it
// reads back, so every file gridrt writes goes through one writer.
#pragma once
#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace gridrt {

enum class SampleType : uint8_t { Float, UInt };

struct ImageChannel {
  // "R", "G", "B", "A"; an AOV's "Z", "id", ...; in a multi-layer file "depth.Z",
  // "primid.id" (OpenEXR's layer.channel naming).
  std::string name;
  SampleType type = SampleType::Float;
  std::vector<float> floats;    // width * height values, row-major, row 0 = top (Float)
  std::vector<uint32_t> uints;  // the same (UInt)
  size_t size() const { return type == SampleType::Float ? floats.size() : uints.size(); }
};

struct LayeredImage {
  int width = 0, height = 0;  // the pixels held: the data window
  int x = 0, y = 0;           // the data window's offset in the display window
  // The display window, from 0,0; 0: the data window itself (x and y then 0).
  int full_width = 0, full_height = 0;
  std::vector<ImageChannel> channels;
  // The colour rays that missed were given. With an alpha channel "A", R, G and B are
  // associated (premultiplied) with it, as OpenEXR defines colour: the rendered colour less
  // the background's share, (1 - A) * background (0 where A is 0), so the rendered colour
  // is R + (1 - A) * background. A PNG stores its colours unassociated from it (R / A, the
  // background where A is 0); float files keep it as the attribute "gridrt:background".
  std::array<float, 3> background{0.0f, 0.0f, 0.0f};
};

// An image's pixels as floats, every channel interleaved (readImage).
struct ImageData {
  int width = 0, height = 0, channels = 0;
  std::vector<float> pixels;  // row-major, row 0 = top, channels interleaved
};

// Channel `c` of `count` interleaved float channels (width * height pixels).
ImageChannel floatChannel(const std::string& name, const std::vector<float>& interleaved, int count,
                          int c);
// Signed 32-bit values (ids, -1 for a miss) as an unsigned channel: -1 is stored as
// 2^32 - 1, the same bits (two's complement).
ImageChannel idChannel(const std::string& name, const std::vector<int32_t>& ids);
// The index of the channel named `name`, or -1.
int channelIndex(const LayeredImage& image, const std::string& name);
// What every encoder checks first: a positive size, some channels, each of width * height
// values. Throws RenderError with a one-line message.
void checkImage(const LayeredImage& image);
// The float colour channel `name` ("R", "G" or "B"); throws RenderError when it is missing
// or holds integers.
const ImageChannel& colourChannel(const LayeredImage& image, const char* name);

}  // namespace gridrt
