#include "texture_sampling.h"

#include <algorithm>
#include <cmath>

namespace gridrt {

int wrapTexel(double i, int n, TextureWrap wrap) {
  if (!std::isfinite(i)) i = 0.0;
  switch (wrap) {
    case TextureWrap::ClampToEdge:
      return int(std::clamp(i, 0.0, double(n - 1)));
    case TextureWrap::MirroredRepeat: {
      double m = std::fmod(i, 2.0 * n);
      if (m < 0.0) m += 2.0 * n;
      const int k = std::min(int(m), 2 * n - 1);
      return k < n ? k : 2 * n - 1 - k;
    }
    case TextureWrap::Repeat:
    default: {
      double m = std::fmod(i, double(n));
      if (m < 0.0) m += n;
      return std::min(int(m), n - 1);
    }
  }
}

namespace {

const glm::vec4& texel(const TexelLevel& level, const Texture& texture, double x, double y) {
  const int i = wrapTexel(x, level.width, texture.wrap_s);
  const int j = wrapTexel(y, level.height, texture.wrap_t);
  return level.texels[size_t(j) * size_t(level.width) + size_t(i)];
}

}  // namespace

glm::vec4 sampleLevel(const TexelLevel& level, const Texture& texture, glm::vec2 uv,
                      TextureFilter filter) {
  const double x = std::isnan(uv.x) ? 0.0 : double(uv.x) * level.width;
  const double y = std::isnan(uv.y) ? 0.0 : double(uv.y) * level.height;
  if (filter == TextureFilter::Nearest) return texel(level, texture, std::floor(x), std::floor(y));
  // Texel centres sit at half-integers: the four around (x, y) and the weights between.
  const double fx = x - 0.5, fy = y - 0.5;
  const double x0 = std::floor(fx), y0 = std::floor(fy);
  const float ax = std::isfinite(fx - x0) ? float(fx - x0) : 0.0f;
  const float ay = std::isfinite(fy - y0) ? float(fy - y0) : 0.0f;
  const glm::vec4 top =
      glm::mix(texel(level, texture, x0, y0), texel(level, texture, x0 + 1, y0), ax);
  const glm::vec4 bottom =
      glm::mix(texel(level, texture, x0, y0 + 1), texel(level, texture, x0 + 1, y0 + 1), ax);
  return glm::mix(top, bottom, ay);
}

glm::vec4 sampleTexture(const TexelImage& image, const Texture& texture, glm::vec2 uv, float lod) {
  const std::vector<TexelLevel>& levels = image.levels;
  if (!(lod > 0.0f)) return sampleLevel(levels[0], texture, uv, texture.mag_filter);
  if (!texture.mipmaps || levels.size() == 1)
    return sampleLevel(levels[0], texture, uv, texture.min_filter);
  const float last = float(levels.size() - 1);
  if (lod >= last) return sampleLevel(levels.back(), texture, uv, texture.min_filter);
  const int lower = int(lod);
  const float blend = lod - float(lower);
  return glm::mix(sampleLevel(levels[size_t(lower)], texture, uv, texture.min_filter),
                  sampleLevel(levels[size_t(lower) + 1], texture, uv, texture.min_filter), blend);
}

}  // namespace gridrt
