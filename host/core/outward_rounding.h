// Double-precision bounds rounded outwards to float, for conservative boxes and margins
// that the kernels read in float.
#pragma once
#include <cstdint>
#include <cstring>

namespace gridrt {

// The float next to f towards -infinity, for f neither NaN nor -infinity (std::nextafter's
// answer without its library call, so that loops over boxes vectorise): one step of the
// bits, down in magnitude above zero, up below it; below +-0 lies the negative denormal.
inline float floatStepDown(float f) {
  uint32_t bits;
  std::memcpy(&bits, &f, sizeof bits);
  bits = f > 0.0f ? bits - 1u : f < 0.0f ? bits + 1u : 0x80000001u;
  std::memcpy(&f, &bits, sizeof f);
  return f;
}

// The float next to f towards +infinity, for f neither NaN nor +infinity.
inline float floatStepUp(float f) { return -floatStepDown(-f); }

// The largest float <= x.
inline float floatBelow(double x) {
  const float f = float(x);
  return double(f) > x ? floatStepDown(f) : f;
}

// The smallest float >= x.
inline float floatAbove(double x) {
  const float f = float(x);
  return double(f) < x ? floatStepUp(f) : f;
}

}  // namespace gridrt
