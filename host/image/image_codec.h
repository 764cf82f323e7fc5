// What the image module does: the one part of gridrt that links OpenImageIO, built as a
// shared module (codec/) that image_module.h loads the first time an image is read or
// written. The executable itself then needs none of the ~250 libraries OpenImageIO pulls
// in: `gridrt --version`, `--help` and `--list-devices` start without them
// (docs/performance.md, "Start-up").
#pragma once
#include <string>
#include <vector>

#include "layered_image.h"

namespace gridrt {

// The module's functions. Each throws RenderError with a one-line message.
struct ImageCodec {
  // The bytes of `image` as a file of `format` ("png", "jpg", "exr", "tif", "hdr";
  // image_format.h). 8-bit formats take the channels R, G, B and, for PNG, A.
  std::vector<unsigned char> (*encode)(const LayeredImage& image, const std::string& format);
  // A file's first subimage: 32-bit integer channels as UInt, every other channel as
  // float (8- and 16-bit values to [0, 1]), with its data and display windows.
  LayeredImage (*read)(const std::string& path);
  // Encoded bytes (a glTF texture) decoded as image_decoding.h says.
  ImageData (*decode)(const std::vector<unsigned char>& bytes, const std::string& format_hint,
                      const std::string& label, long long max_pixels);
  float (*srgb_to_linear)(float encoded);
};

}  // namespace gridrt

// The module's one exported symbol: its functions.
#define GRIDRT_IMAGE_CODEC_ENTRY "gridrt_image_codec"
extern "C" const gridrt::ImageCodec* gridrt_image_codec();
