// Texture lookups as a glTF sampler asks for them: wrap modes per axis, nearest or
// bilinear filtering within a level, and between mip levels a linear blend chosen by the
// footprint's level of detail. glTF's texture coordinates put (0, 0) at the top-left
// corner of the image's first texel and (1, 1) at the bottom-right corner of its last.
#pragma once
#include <glm/glm.hpp>

#include "scene.h"

namespace gridrt {

// Texel index i (any integer, as a double so that huge coordinates do not overflow) on an
// axis of n texels, wrapped as `wrap` says.
int wrapTexel(double i, int n, TextureWrap wrap);

// One level at uv: the texel containing uv (Nearest), or the four texels around it
// weighted bilinearly (Linear), each index wrapped. A NaN coordinate reads as 0.
glm::vec4 sampleLevel(const TexelLevel& level, const Texture& texture, glm::vec2 uv,
                      TextureFilter filter);

// The image at uv for a footprint `lod` = log2(footprint width in level-0 texels):
// magnified (lod <= 0) with the texture's mag_filter on level 0; minified with its
// min_filter, on level 0 when the texture has no mip-maps, else blended linearly between
// the two levels around lod (the last level beyond them). `image` must not be empty.
glm::vec4 sampleTexture(const TexelImage& image, const Texture& texture, glm::vec2 uv, float lod);

}  // namespace gridrt
