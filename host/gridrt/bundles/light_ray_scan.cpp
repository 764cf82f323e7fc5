#include "light_ray_scan.h"

// One target, the vector unit the build's flags select (-march=native by default), as in
// dda_packet.cpp: no dispatch at run time.
#define HWY_COMPILE_ONLY_STATIC 1
#include <hwy/highway.h>

#include <algorithm>
#include <cstddef>

namespace gridrt {

namespace {

namespace hn = hwy::HWY_NAMESPACE;

// The face of direction w (from the light), 2 * axis + (w[axis] < 0), and the point
// (w[b], w[c]) / |w[axis]| in [-1, 1]^2 where it meets that face; false for w = 0.
bool onFace(const glm::vec3& w, int& face, float& u, float& v) {
  const glm::vec3 m = glm::abs(w);
  const int a = m.x >= m.y && m.x >= m.z ? 0 : (m.y >= m.z ? 1 : 2);
  if (!(m[a] > 0.0f)) return false;
  face = 2 * a + (w[a] < 0.0f);
  u = w[kOtherAxes[a][0]] / m[a];
  v = w[kOtherAxes[a][1]] / m[a];
  return true;
}

// The rays are read as packets of floats: ox, oy, oz, tmin, dx, dy, dz, tmax.
static_assert(sizeof(GrRay) == 8 * sizeof(float) && offsetof(GrRay, dx) == 4 * sizeof(float) &&
              offsetof(GrRay, tmax) == 7 * sizeof(float));

using Df = hn::ScalableTag<float>;
using Vf = hn::Vec<Df>;

// std::min and std::max lane by lane, NaN handling included: (b < a) ? b : a and
// (a < b) ? b : a.
Vf minLike(Vf a, Vf b) { return hn::IfThenElse(hn::Lt(b, a), b, a); }
Vf maxLike(Vf a, Vf b) { return hn::IfThenElse(hn::Lt(a, b), b, a); }

// The lanes of x folded with `fold` onto `init`, lane by lane.
template <typename Fold>
float foldLanes(Vf x, float init, Fold fold) {
  const Df df;
  alignas(64) float lanes[hn::MaxLanes(df)];
  hn::Store(x, df, lanes);
  for (size_t k = 0; k < hn::Lanes(df); ++k) init = fold(init, lanes[k]);
  return init;
}

}  // namespace

float endToLightSquared(const GrRay& ray, const glm::vec3& light) {
  const glm::vec3 end =
      glm::vec3(ray.ox, ray.oy, ray.oz) + ray.tmax * glm::vec3(ray.dx, ray.dy, ray.dz);
  const glm::vec3 off = end - light;
  return glm::dot(off, off);
}

void scanLightRay(const GrRay& ray, const glm::vec3& light, int& face, float& u, float& v,
                  double& depth, LightRayScan& scan) {
  const glm::vec3 d(ray.dx, ray.dy, ray.dz);
  const float off = endToLightSquared(ray, light);
  scan.miss_squared = std::max(scan.miss_squared, std::isfinite(off) ? off : INFINITY);
  const float ray_reach =
      std::fabs(ray.ox) + std::fabs(ray.oy) + std::fabs(ray.oz) + std::fabs(ray.tmax);
  scan.reach = std::max(scan.reach, std::isfinite(ray_reach) ? ray_reach : INFINITY);
  const float length_squared = glm::dot(d, d);
  scan.min_length_squared =
      std::min(scan.min_length_squared, length_squared == length_squared ? length_squared : 0.0f);
  face = 0;  // no direction (onFace false): any cell will do
  u = v = 0.0f;
  onFace(-d, face, u, v);
  depth = originDepth(ray, light, face);
  scan.windows[face].add(u, v);
}

void scanLightRays(const GrRay* rays, size_t first, size_t last, const glm::vec3& light,
                   int* face_of, float* uv, double* depth, LightRayScan& scan) {
  const Df df;
  const hn::RebindToSigned<Df> di;
  const hn::Repartition<double, Df> dd;
  const hn::Half<Df> dh;
  const size_t N = hn::Lanes(df);
  const Vf zero = hn::Zero(df), inf = hn::Set(df, INFINITY);
  const Vf lx = hn::Set(df, light.x), ly = hn::Set(df, light.y), lz = hn::Set(df, light.z);
  Vf miss = zero, reach = zero, min_length = inf;
  Vf umin[6], umax[6], vmin[6], vmax[6];
  size_t count[6] = {};
  for (int f = 0; f < 6; ++f) {
    umin[f] = vmin[f] = inf;
    umax[f] = vmax[f] = hn::Neg(inf);
  }
  size_t r = first;
  for (; r + N <= last; r += N) {
    // N rays as 2N quads of floats: even quads (ox, oy, oz, tmin), odd (dx, dy, dz, tmax).
    const float* at = &rays[r].ox;
    Vf a0, a1, a2, a3, b0, b1, b2, b3;
    hn::LoadInterleaved4(df, at, a0, a1, a2, a3);
    hn::LoadInterleaved4(df, at + 4 * N, b0, b1, b2, b3);
    const Vf ox = hn::ConcatEven(df, b0, a0), oy = hn::ConcatEven(df, b1, a1),
             oz = hn::ConcatEven(df, b2, a2);
    const Vf dx = hn::ConcatOdd(df, b0, a0), dy = hn::ConcatOdd(df, b1, a1),
             dz = hn::ConcatOdd(df, b2, a2), tmax = hn::ConcatOdd(df, b3, a3);
    // endToLightSquared: (o + tmax * d) - light, its dot with itself.
    const Vf fx = hn::Sub(hn::Add(ox, hn::Mul(tmax, dx)), lx);
    const Vf fy = hn::Sub(hn::Add(oy, hn::Mul(tmax, dy)), ly);
    const Vf fz = hn::Sub(hn::Add(oz, hn::Mul(tmax, dz)), lz);
    const Vf off = hn::Add(hn::Add(hn::Mul(fx, fx), hn::Mul(fy, fy)), hn::Mul(fz, fz));
    miss = maxLike(miss, hn::IfThenElse(hn::IsFinite(off), off, inf));
    const Vf ray_reach =
        hn::Add(hn::Add(hn::Add(hn::Abs(ox), hn::Abs(oy)), hn::Abs(oz)), hn::Abs(tmax));
    reach = maxLike(reach, hn::IfThenElse(hn::IsFinite(ray_reach), ray_reach, inf));
    const Vf length = hn::Add(hn::Add(hn::Mul(dx, dx), hn::Mul(dy, dy)), hn::Mul(dz, dz));
    min_length = minLike(min_length, hn::IfThenElseZero(hn::Eq(length, length), length));
    // onFace(-d): the axis of the largest |d| (x, then y, on ties), its sign, and the
    // other two coordinates over it.
    const Vf mx = hn::Abs(dx), my = hn::Abs(dy), mz = hn::Abs(dz);
    const auto on_x = hn::And(hn::Ge(mx, my), hn::Ge(mx, mz));
    const auto on_y = hn::AndNot(on_x, hn::Ge(my, mz));
    const Vf wx = hn::Neg(dx), wy = hn::Neg(dy), wz = hn::Neg(dz);
    const Vf m = hn::IfThenElse(on_x, mx, hn::IfThenElse(on_y, my, mz));
    const Vf wa = hn::IfThenElse(on_x, wx, hn::IfThenElse(on_y, wy, wz));
    const Vf wb = hn::IfThenElse(on_x, wy, hn::IfThenElse(on_y, wz, wx));
    const Vf wc = hn::IfThenElse(on_x, wz, hn::IfThenElse(on_y, wx, wy));
    const auto valid = hn::Gt(m, zero);
    const Vf u = hn::IfThenElseZero(valid, hn::Div(wb, m));
    const Vf v = hn::IfThenElseZero(valid, hn::Div(wc, m));
    const auto negative = hn::And(valid, hn::Lt(wa, zero));
    const auto axis2 =
        hn::IfThenElse(hn::RebindMask(di, on_x), hn::Zero(di),
                       hn::IfThenElse(hn::RebindMask(di, on_y), hn::Set(di, 2), hn::Set(di, 4)));
    const auto face = hn::IfThenElseZero(
        hn::RebindMask(di, valid),
        hn::Add(axis2, hn::IfThenElseZero(hn::RebindMask(di, negative), hn::Set(di, 1))));
    hn::StoreU(face, di, face_of + r);
    hn::StoreInterleaved2(u, v, df, uv + 2 * r);
    // originDepth: the origin's coordinate on the face's axis (x without a direction)
    // less the light's, or the light's less it on a negative face, in double.
    const auto along_x = hn::Or(hn::Not(valid), on_x), along_y = hn::AndNot(hn::Not(valid), on_y);
    const Vf o_axis = hn::IfThenElse(along_x, ox, hn::IfThenElse(along_y, oy, oz));
    const Vf l_axis = hn::IfThenElse(along_x, lx, hn::IfThenElse(along_y, ly, lz));
    const Vf minuend = hn::IfThenElse(negative, l_axis, o_axis);
    const Vf subtrahend = hn::IfThenElse(negative, o_axis, l_axis);
    const auto infinite = hn::Set(dd, INFINITY);
    auto lower = hn::Sub(hn::PromoteTo(dd, hn::LowerHalf(dh, minuend)),
                         hn::PromoteTo(dd, hn::LowerHalf(dh, subtrahend)));
    auto upper = hn::Sub(hn::PromoteTo(dd, hn::UpperHalf(dh, minuend)),
                         hn::PromoteTo(dd, hn::UpperHalf(dh, subtrahend)));
    hn::StoreU(hn::IfThenElse(hn::IsNaN(lower), infinite, lower), dd, depth + r);
    hn::StoreU(hn::IfThenElse(hn::IsNaN(upper), infinite, upper), dd, depth + r + N / 2);
    // FaceWindow::add of each lane on its face.
    for (int f = 0; f < 6; ++f) {
      const auto here = hn::RebindMask(df, hn::Eq(face, hn::Set(di, f)));
      umin[f] = hn::IfThenElse(here, minLike(umin[f], u), umin[f]);
      umax[f] = hn::IfThenElse(here, maxLike(umax[f], u), umax[f]);
      vmin[f] = hn::IfThenElse(here, minLike(vmin[f], v), vmin[f]);
      vmax[f] = hn::IfThenElse(here, maxLike(vmax[f], v), vmax[f]);
      count[f] += hn::CountTrue(df, here);
    }
  }
  auto lesser = [](float a, float b) { return std::min(a, b); };
  auto greater = [](float a, float b) { return std::max(a, b); };
  scan.miss_squared = foldLanes(miss, scan.miss_squared, greater);
  scan.reach = foldLanes(reach, scan.reach, greater);
  scan.min_length_squared = foldLanes(min_length, scan.min_length_squared, lesser);
  for (int f = 0; f < 6; ++f) {
    FaceWindow lanes;
    lanes.umin = foldLanes(umin[f], INFINITY, lesser);
    lanes.umax = foldLanes(umax[f], -INFINITY, greater);
    lanes.vmin = foldLanes(vmin[f], INFINITY, lesser);
    lanes.vmax = foldLanes(vmax[f], -INFINITY, greater);
    lanes.count = count[f];
    scan.windows[f].merge(lanes);
  }
  for (; r < last; ++r)
    scanLightRay(rays[r], light, face_of[r], uv[2 * r], uv[2 * r + 1], depth[r], scan);
}

void cellsOfLightRays(const std::array<FaceWindow, 6>& faces, const int* face_of, const float* uv,
                      size_t first, size_t last, int* cell_of) {
  const Df df;
  const hn::RebindToSigned<Df> di;
  const size_t N = hn::Lanes(df);
  size_t r = first;
  for (; r + N <= last; r += N) {
    const auto face = hn::LoadU(di, face_of + r);
    Vf u, v;
    hn::LoadInterleaved2(df, uv + 2 * r, u, v);
    // Each lane's face's values, by selects (six faces need not fit a table of lanes).
    auto ofFace = [&](auto d, auto value) {
      auto x = hn::Set(d, value(faces[0]));
      for (int f = 1; f < 6; ++f)
        x = hn::IfThenElse(hn::RebindMask(d, hn::Eq(face, hn::Set(di, f))),
                           hn::Set(d, value(faces[f])), x);
      return x;
    };
    const Vf u0 = ofFace(df, [](const FaceWindow& w) { return w.u0; });
    const Vf v0 = ofFace(df, [](const FaceWindow& w) { return w.v0; });
    const Vf su = ofFace(df, [](const FaceWindow& w) { return w.su; });
    const Vf sv = ofFace(df, [](const FaceWindow& w) { return w.sv; });
    const Vf last_cell = ofFace(df, [](const FaceWindow& w) { return float(w.res - 1); });
    const auto res = ofFace(di, [](const FaceWindow& w) { return w.res; });
    const auto first_cell = ofFace(di, [](const FaceWindow& w) { return int(w.first_cell); });
    // FaceWindow::cellOf's index: int(std::max(0, std::min(res - 1, x))).
    auto index = [&](Vf x) {
      const Vf below = hn::IfThenElse(hn::Lt(x, last_cell), x, last_cell);
      const Vf zero = hn::Zero(df);
      return hn::ConvertTo(di, hn::IfThenElse(hn::Lt(zero, below), below, zero));
    };
    const auto column = index(hn::Mul(hn::Sub(u, u0), su));
    const auto row = index(hn::Mul(hn::Sub(v, v0), sv));
    hn::StoreU(hn::Add(first_cell, hn::Add(hn::Mul(row, res), column)), di, cell_of + r);
  }
  for (; r < last; ++r) cell_of[r] = int(faces[face_of[r]].cellOf(uv[2 * r], uv[2 * r + 1]));
}

}  // namespace gridrt
