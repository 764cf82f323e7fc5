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

// Renderer::worthTracing of a weight (r, g, b): std::max({r, g, b}) >= floor.
int worthTracing(float r, float g, float b, float floor) {
  float largest = r;
  largest = largest < g ? g : largest;
  largest = largest < b ? b : largest;
  return largest >= floor ? 1 : 0;
}

// The one-hit loop's spawned rays in lanes, for one kind of offset (as offsetLanes): its
// expressions term by term in GLM's order, each branch made a select.
template <bool kRobust>
void spawnLanes(const SurfaceLanes& s, const PlainMaterial* materials, float min_path_weight,
                PlainLanes& p, SpawnLanes& out) {
#pragma omp simd
  for (int k = 0; k < L; ++k) {
    const PlainMaterial& m = materials[p.material[k]];
    const float dx = s.dx[k], dy = s.dy[k], dz = s.dz[k];
    const float nx = s.nx[k], ny = s.ny[k], nz = s.nz[k];
    const float gx = s.gx[k], gy = s.gy[k], gz = s.gz[k];
    const float wr = p.wr[k], wg = p.wg[k], wb = p.wb[k];
    const float dn = dx * nx + dy * ny + dz * nz;  // glm::dot(d, n)
    // Transmission: eta, fresnelDielectric(-dot(d, n), eta) and refractDirection.
    const float eta = s.backface[k] ? m.ior : 1.0f / m.ior;
    float cos_i = -dn;
    cos_i = cos_i < 0.0f ? 0.0f : (1.0f < cos_i ? 1.0f : cos_i);  // std::clamp(cos_i, 0, 1)
    const float sin2_f = eta * eta * (1.0f - cos_i * cos_i);
    const float cos_f = std::sqrt(1.0f - sin2_f);
    const float rs = (eta * cos_i - cos_f) / (eta * cos_i + cos_f);
    const float rp = (cos_i - eta * cos_f) / (cos_i + eta * cos_f);
    float f = sin2_f >= 1.0f ? 1.0f : 0.5f * (rs * rs + rp * rp);
    const float tr = wr * m.transmission * (1.0f - f) * m.base_color.x;
    const float tg = wg * m.transmission * (1.0f - f) * m.base_color.y;
    const float tb = wb * m.transmission * (1.0f - f) * m.base_color.z;
    const float ci = -dn, sin2_t = eta * eta * (1.0f - ci * ci);
    const float bend = eta * ci - std::sqrt(1.0f - sin2_t);
    const float vx = eta * dx + bend * nx, vy = eta * dy + bend * ny, vz = eta * dz + bend * nz;
    const float inv = 1.0f / std::sqrt(vx * vx + vy * vy + vz * vz);  // glm::normalize
    const float tx = vx * inv, ty = vy * inv, tz = vz * inv;
    const int through =
        (f < 1.0f) & !(sin2_t >= 1.0f) & ((tx * gx + ty * gy + tz * gz) < 0.0f) ? 1 : 0;
    f = through ? f : 1.0f;  // total internal reflection
    const int transmits = m.transmission > 0.0f ? 1 : 0;
    out.refract[k] = transmits & through & worthTracing(tr, tg, tb, min_path_weight);
    out.rdx[k] = tx, out.rdy[k] = ty, out.rdz[k] = tz;
    out.rwr[k] = tr, out.rwg[k] = tg, out.rwb[k] = tb;
    // Its origin: offsetRayOrigin(p, -ng, offset distance).
    const float distance = p.offset[k];
    const float bx = s.px[k] + distance * -gx, by = s.py[k] + distance * -gy,
                bz = s.pz[k] + distance * -gz;
    p.plain[k] &= finite(bx) & finite(by) & finite(bz);
    out.rox[k] = offsetAxis(bx, -gx, kRobust);
    out.roy[k] = offsetAxis(by, -gy, kRobust);
    out.roz[k] = offsetAxis(bz, -gz, kRobust);
    // Reflection: the mirror's weight, plus the transmission's reflected share.
    const float share = transmits ? m.transmission * f : 0.0f;
    const float mr = transmits ? m.mirror.x + share : m.mirror.x;
    const float mg = transmits ? m.mirror.y + share : m.mirror.y;
    const float mb = transmits ? m.mirror.z + share : m.mirror.z;
    const float qr = wr * mr, qg = wg * mg, qb = wb * mb;
    out.reflect[k] =
        (mr * mr + mg * mg + mb * mb > 0.0f ? 1 : 0) & worthTracing(qr, qg, qb, min_path_weight);
    out.fwr[k] = qr, out.fwg[k] = qg, out.fwb[k] = qb;
    // reflectDirection(d, n), or about ng where that would not leave the surface.
    const float twice_n = 2.0f * dn;
    const float ax = dx - twice_n * nx, ay = dy - twice_n * ny, az = dz - twice_n * nz;
    const float twice_g = 2.0f * (dx * gx + dy * gy + dz * gz);
    const int about_g = ax * gx + ay * gy + az * gz <= 0.0f ? 1 : 0;
    out.fdx[k] = about_g ? dx - twice_g * gx : ax;
    out.fdy[k] = about_g ? dy - twice_g * gy : ay;
    out.fdz[k] = about_g ? dz - twice_g * gz : az;
  }
}

}  // namespace

void computeSpawnLanes(const SurfaceLanes& s, const PlainMaterial* materials,
                       const RayOffset& offset, float min_path_weight, PlainLanes& p,
                       SpawnLanes& out) {
  if (offset.robust)
    spawnLanes<true>(s, materials, min_path_weight, p, out);
  else
    spawnLanes<false>(s, materials, min_path_weight, p, out);
}

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
