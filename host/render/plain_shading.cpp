#include "plain_shading.h"

#include <algorithm>
#include <cfloat>
#include <cmath>

namespace gridrt {

namespace {

constexpr int L = kSurfaceLanes;

// 1 for a finite x (ints, not bools: a bool lane would make GCC leave the loop scalar).
int finite(float x) { return std::fabs(x) <= FLT_MAX ? 1 : 0; }

// offsetRayOrigin along one axis for a finite sum p + distance * n: with the robust offset
// one ulp further where n is not zero.
float offsetAxis(float sum, float n, bool robust) {
  return robust && n != 0.0f ? nextFiniteFloat(sum, n > 0.0f) : sum;
}

// rayOffsetDistance and offsetRayOrigin in lanes, for one kind of offset (a loop-invariant
// choice inside the loop kept GCC from vectorising it).
template <bool kRobust>
void offsetLanes(const SurfaceLanes& s, float epsilon, PlainLanes& p) {
#pragma omp simd
  for (int k = 0; k < L; ++k) {
    float distance = epsilon;
    if constexpr (kRobust) {  // the largest magnitude of the point and the ray's origin
      float magnitude = 0.0f;
      magnitude = std::max(magnitude, std::max(std::fabs(s.px[k]), std::fabs(s.ox[k])));
      magnitude = std::max(magnitude, std::max(std::fabs(s.py[k]), std::fabs(s.oy[k])));
      magnitude = std::max(magnitude, std::max(std::fabs(s.pz[k]), std::fabs(s.oz[k])));
      distance = kHitPointErrorUlps * kUlpOfOne * magnitude;
    }
    p.offset[k] = distance;
    const float x = s.px[k] + distance * s.gx[k], y = s.py[k] + distance * s.gy[k],
                z = s.pz[k] + distance * s.gz[k];
    // Every input and sum finite, or the one-hit loop (nextFloat's other branch).
    const int inputs = finite(s.px[k]) & finite(s.py[k]) & finite(s.pz[k]) & finite(s.ox[k]) &
                       finite(s.oy[k]) & finite(s.oz[k]) & finite(s.gx[k]) & finite(s.gy[k]) &
                       finite(s.gz[k]);
    p.plain[k] &= inputs & finite(x) & finite(y) & finite(z);
    p.ax[k] = offsetAxis(x, s.gx[k], kRobust);
    p.ay[k] = offsetAxis(y, s.gy[k], kRobust);
    p.az[k] = offsetAxis(z, s.gz[k], kRobust);
  }
}

}  // namespace

void computePlainLanes(const SurfaceLanes& s, const PlainMaterial* materials, float ambient,
                       const RayOffset& offset, PlainLanes& p) {
#pragma omp simd
  for (int k = 0; k < L; ++k) {
    // The own light: weight * (emissive + ambient * diffuse), GLM's order.
    const PlainMaterial& m = materials[p.material[k]];
    p.lr[k] = p.wr[k] * (m.emissive.x + ambient * m.diffuse.x);
    p.lg[k] = p.wg[k] * (m.emissive.y + ambient * m.diffuse.y);
    p.lb[k] = p.wb[k] * (m.emissive.z + ambient * m.diffuse.z);
    p.plain[k] = m.plain;
  }
  if (offset.robust)
    offsetLanes<true>(s, offset.epsilon, p);
  else
    offsetLanes<false>(s, offset.epsilon, p);
}

void computePlainLight(const PlainLanes& p, const PlainMaterial* materials, const LightLanes& light,
                       PlainLightLanes& out) {
#pragma omp simd
  for (int k = 0; k < L; ++k) {
    const PlainMaterial& m = materials[p.material[k]];
    const float e[3] = {light.ex[k], light.ey[k], light.ez[k]};
    const float w[3] = {p.wr[k], p.wg[k], p.wb[k]};
    const float diffuse[3] = {m.diffuse.x, m.diffuse.y, m.diffuse.z};
    const float specular[3] = {m.specular.x, m.specular.y, m.specular.z};
    float c[3];
    for (int a = 0; a < 3; ++a)  // diffuse / pi * e * cos_theta + specular * e * highlight
      c[a] = w[a] * (diffuse[a] / kPi * e[a] * light.cos_theta[k] +
                     specular[a] * e[a] * light.highlight[k]);
    out.cr[k] = c[0], out.cg[k] = c[1], out.cb[k] = c[2];
    // glm::dot(c, c) != 0, as the one-hit loop tests it.
    out.emit[k] = light.lit[k] && c[0] * c[0] + c[1] * c[1] + c[2] * c[2] != 0.0f;
  }
}

}  // namespace gridrt
