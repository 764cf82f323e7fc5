// PNG files written without the image module: libpng (about ten libraries with its
// dependencies) instead of OpenImageIO (~250, 0.3 s to load on a 2-core AMD EPYC, KVM,
// 2026-12-03), so a render to PNG, the default output, starts and ends without it.
// The pixels equal those the module writes (tests/image/png_encoder_test.cpp).
#pragma once
#include <vector>

#include "layered_image.h"

namespace gridrt {

// The bytes of `image` as an 8-bit PNG: R, G, B (and A when the image has it), each
// clamped to [0, 1] (NaN as 0) and sRGB-encoded. With alpha, the colour is stored
// unassociated, as PNG defines it (layered_image.h): divided by the alpha where the pixel
// is partly covered, the background where it is not covered. Throws RenderError with a
// one-line message for an image it cannot hold (a window of a larger one, missing or
// integer colour channels).
std::vector<unsigned char> encodePng(const LayeredImage& image);

// sRGB's encoding of a linear value in [0, 1] (IEC 61966-2-1), rounded to 8 bits.
unsigned char linearToSrgb8(float linear);

}  // namespace gridrt
