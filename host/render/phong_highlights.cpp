#include "phong_highlights.h"

// One target, the vector unit the build's flags select (-march=native by default), as in
// dda_packet.cpp: no dispatch at run time.
#define HWY_COMPILE_ONLY_STATIC 1
#include <hwy/highway.h>
// The contrib header after the core one, as Highway asks.
#include <hwy/contrib/math/math-inl.h>

#include <algorithm>

namespace gridrt {
namespace {

namespace hn = hwy::HWY_NAMESPACE;

// rv^exponent lane by lane: exp(exponent * log(rv)) where rv > 0, rv itself where the
// exponent is 1, else 0 (std::pow(0, e >= 1) is 0).
template <class D>
hn::VFromD<D> power(D d, hn::VFromD<D> rv, hn::VFromD<D> exponent) {
  const auto zero = hn::Zero(d);
  const auto positive = hn::Gt(rv, zero);
  // log(1) where rv is not positive: no NaN or infinity in a lane that is thrown away.
  const auto x = hn::IfThenElse(positive, rv, hn::Set(d, 1.0f));
  const auto p = hn::Exp(d, hn::Mul(exponent, hn::Log(d, x)));
  const auto one = hn::Eq(exponent, hn::Set(d, 1.0f));
  return hn::IfThenElseZero(positive, hn::IfThenElse(one, rv, p));
}

}  // namespace

void computeHighlights(const SurfaceLanes& s, const float* exponent, LightLanes& light) {
  // rv as the one-hit code wrote it: r = reflect(-l, n) = -l - 2 (-l . n) n, rv = max(0,
  // r . -d), GLM's dot products.
  for (int k = 0; k < kSurfaceLanes; ++k) {
    const float ax = -light.lx[k], ay = -light.ly[k], az = -light.lz[k];
    const float an = 2.0f * dot3(ax, ay, az, s.nx[k], s.ny[k], s.nz[k]);
    const float rx = ax - an * s.nx[k], ry = ay - an * s.ny[k], rz = az - an * s.nz[k];
    light.rv[k] = std::max(0.0f, dot3(rx, ry, rz, -s.dx[k], -s.dy[k], -s.dz[k]));
  }
  const hn::ScalableTag<float> d;  // 16 lanes with AVX-512: one step
  for (int k = 0; k < kSurfaceLanes; k += int(hn::Lanes(d)))
    hn::Store(power(d, hn::Load(d, light.rv + k), hn::LoadU(d, exponent + k)), d,
              light.highlight + k);
}

float phongHighlight(float rv, float exponent) {
  const hn::CappedTag<float, 1> d;
  return hn::GetLane(power(d, hn::Set(d, rv), hn::Set(d, exponent)));
}

}  // namespace gridrt
