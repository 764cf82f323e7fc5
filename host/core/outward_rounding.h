// Double-precision bounds rounded outwards to float, for conservative boxes and margins
// that the kernels read in float.
#pragma once
#include <cmath>
#include <limits>

namespace gridrt {

// The largest float <= x.
inline float floatBelow(double x) {
  const float f = float(x);
  return double(f) > x ? std::nextafter(f, -std::numeric_limits<float>::infinity()) : f;
}

// The smallest float >= x.
inline float floatAbove(double x) {
  const float f = float(x);
  return double(f) < x ? std::nextafter(f, std::numeric_limits<float>::infinity()) : f;
}

}  // namespace gridrt
