// The mip levels of a texel image: each level half the size of the one before (rounded
// down, at least 1) down to 1x1, each texel the mean of the 2x2 texels it covers (of an odd
// size's last row or column, the 2x3, 3x2 or 3x3 it covers, so that no texel is lost).
#pragma once
#include "scene.h"

namespace gridrt {

// `base` as level 0 and the levels below it.
TexelImage withMipLevels(TexelLevel base);

}  // namespace gridrt
