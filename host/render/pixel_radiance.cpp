#include "pixel_radiance.h"

#include <algorithm>

#include "parallel_loops.h"
#include "prefault.h"

namespace gridrt {

void PixelRadiance::clear(size_t pixels) {
  resizeFaultedIn(rgb_, 3 * pixels);
  parallelSlices(parallelSliceCount(), [&](int me, int count) {
    const auto [first, last] = sliceRange(rgb_.size(), me, count);
    std::fill(rgb_.begin() + first, rgb_.begin() + last, 0.0f);
  });
}

}  // namespace gridrt
