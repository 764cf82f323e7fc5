// PNG files made in a test through OpenImageIO, as the bytes a glTF file embeds. For the
// tests that link OpenImageIO (through gridrt_image) only.
#pragma once
#include <OpenImageIO/imageio.h>

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "run_command.h"
#include "test_support.h"

namespace gridrt::test {

// A width x height PNG of 8-bit `values` (channels interleaved, row 0 at the top).
inline std::vector<unsigned char> encodePng(int width, int height, int channels,
                                            const std::vector<uint8_t>& values) {
  static int counter = 0;
  const std::string path = tempPath("encoded" + std::to_string(counter++) + ".png");
  auto out = OIIO::ImageOutput::create(path);
  OIIO::ImageSpec spec(width, height, channels, OIIO::TypeDesc::UINT8);
  spec.attribute("oiio:UnassociatedAlpha", 1);  // the values as given, alpha or not
  if (!out || !out->open(path, spec) || !out->write_image(OIIO::TypeDesc::UINT8, values.data()) ||
      !out->close())
    return {};
  const std::string bytes = readWholeFile(path);
  return std::vector<unsigned char>(bytes.begin(), bytes.end());
}

// The sRGB transfer function undone, as the sRGB specification writes it (IEC 61966-2-1).
inline double srgbDecoded(double encoded) {
  return encoded <= 0.04045 ? encoded / 12.92 : std::pow((encoded + 0.055) / 1.055, 2.4);
}

}  // namespace gridrt::test
