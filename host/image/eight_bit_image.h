// An image's 8-bit codes as PNG and JPEG hold them, made the same way for both writers (the
// PNG encoder, png_encoder.h, and the image module's JPEG).
#pragma once
#include <string>
#include <vector>

#include "layered_image.h"

namespace gridrt {

struct EightBitImage {
  int channels = 3;                  // R, G, B and, with alpha, A
  std::vector<unsigned char> codes;  // width * height * channels, row-major, row 0 = top
};

// R, G, B (and A when the image has one and `format` is "png") each clamped to [0, 1] (NaN
// as 0) and sRGB-encoded, rounded to the nearest code, on all cores. With alpha, the colour
// is stored unassociated, as PNG defines it (layered_image.h): divided by the alpha where
// the pixel is partly covered, the background where it is not covered. Throws RenderError
// with a one-line message for what an 8-bit file cannot hold (a window of a larger image,
// missing or integer colour channels, alpha in a JPEG).
EightBitImage eightBitImage(const LayeredImage& image, const std::string& format);

// sRGB's encoding of a linear value in [0, 1] (IEC 61966-2-1) in float, rounded to 8 bits.
unsigned char linearToSrgb8(float linear);

}  // namespace gridrt
