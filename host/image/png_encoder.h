// PNG files written without the image module: libpng (about ten libraries with its
// dependencies) instead of OpenImageIO (~250, 0.3 s to load on a 2-core AMD EPYC, KVM,
// 2026-12-03), so a render to PNG, the default output, starts and ends without it.
#pragma once
#include <vector>

#include "layered_image.h"

namespace gridrt {

// The bytes of `image` as an 8-bit PNG of its codes (eight_bit_image.h), with alpha when
// the image has it. Throws RenderError with a one-line message for an image it cannot hold.
std::vector<unsigned char> encodePng(const LayeredImage& image);

}  // namespace gridrt
