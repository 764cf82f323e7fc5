#include "mip_levels.h"

#include <algorithm>

#include "parallel_loops.h"

namespace gridrt {
namespace {

// The source texels [first, last) one destination texel i of n covers on an axis of m.
void span(int i, int n, int m, int& first, int& last) {
  first = 2 * i;
  last = i + 1 == n ? m : 2 * i + 2;  // the last destination texel takes the odd remainder
  last = std::max(last, first + 1);
  last = std::min(last, m);
  first = std::min(first, m - 1);
}

TexelLevel halved(const TexelLevel& from) {
  TexelLevel to;
  to.width = std::max(1, from.width / 2);
  to.height = std::max(1, from.height / 2);
  to.texels.resize(size_t(to.width) * size_t(to.height));
  parallelFor(int(0), int(to.height), [&](int y) {
    int y0, y1;
    span(y, to.height, from.height, y0, y1);
    for (int x = 0; x < to.width; ++x) {
      int x0, x1;
      span(x, to.width, from.width, x0, x1);
      glm::vec4 sum(0.0f);
      for (int j = y0; j < y1; ++j)
        for (int i = x0; i < x1; ++i)
          sum += from.texels[size_t(j) * size_t(from.width) + size_t(i)];
      to.texels[size_t(y) * size_t(to.width) + size_t(x)] = sum / float((y1 - y0) * (x1 - x0));
    }
  });
  return to;
}

}  // namespace

TexelImage withMipLevels(TexelLevel base) {
  TexelImage image;
  image.levels.push_back(std::move(base));
  while (image.levels.back().width > 1 || image.levels.back().height > 1)
    image.levels.push_back(halved(image.levels.back()));
  return image;
}

}  // namespace gridrt
