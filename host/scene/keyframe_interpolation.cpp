#include "keyframe_interpolation.h"

#include <algorithm>
#include <cmath>
#include <cstddef>

namespace gridrt {
namespace {

// The key group `group` (0 in-tangent, 1 value, 2 out-tangent for CUBICSPLINE; 0 otherwise)
// of key k, component c.
double keyValue(const KeyframeTrack& track, size_t k, int group, int c) {
  const size_t groups = track.interpolation == Interpolation::CubicSpline ? 3 : 1;
  return track.values[(k * groups + size_t(group)) * size_t(track.width) + size_t(c)];
}

// The value of key k as it stands (the value group of a cubic key).
std::vector<double> keyAt(const KeyframeTrack& track, size_t k) {
  const int group = track.interpolation == Interpolation::CubicSpline ? 1 : 0;
  std::vector<double> out(size_t(track.width));
  for (int c = 0; c < track.width; ++c) out[size_t(c)] = keyValue(track, k, group, c);
  return out;
}

glm::dvec4 quaternionOf(const std::vector<double>& v) { return {v[0], v[1], v[2], v[3]}; }

std::vector<double> normalised(std::vector<double> v) {
  double sum = 0.0;
  for (double x : v) sum += x * x;
  const double length = std::sqrt(sum);
  if (length > 0.0)
    for (double& x : v) x /= length;
  return v;
}

}  // namespace

glm::dvec4 slerpShortArc(glm::dvec4 a, glm::dvec4 b, double u) {
  a = glm::normalize(a);
  b = glm::normalize(b);
  double cosine = glm::dot(a, b);
  if (cosine < 0.0) {
    b = -b;
    cosine = -cosine;
  }
  if (cosine > kSlerpLinearAbove) return glm::normalize((1.0 - u) * a + u * b);
  const double angle = std::acos(cosine);
  const double sine = std::sin(angle);
  return (std::sin((1.0 - u) * angle) / sine) * a + (std::sin(u * angle) / sine) * b;
}

std::vector<double> sampleTrack(const KeyframeTrack& track, double t) {
  const size_t keys = track.times.size();
  // Clamped outside the keys (and a single key holds for ever).
  if (keys == 1 || !(t > track.times.front())) return keyAt(track, 0);
  if (t >= track.times.back()) return keyAt(track, keys - 1);
  // The interval [times[k], times[k + 1]) holding t.
  const size_t k =
      size_t(std::upper_bound(track.times.begin(), track.times.end(), t) - track.times.begin()) - 1;
  if (track.interpolation == Interpolation::Step) return keyAt(track, k);
  const double t0 = track.times[k], t1 = track.times[k + 1];
  const double span = t1 - t0;
  const double u = (t - t0) / span;
  std::vector<double> out(size_t(track.width));
  if (track.interpolation == Interpolation::Linear) {
    if (track.quaternion) {
      const glm::dvec4 q =
          slerpShortArc(quaternionOf(keyAt(track, k)), quaternionOf(keyAt(track, k + 1)), u);
      return {q.x, q.y, q.z, q.w};
    }
    for (int c = 0; c < track.width; ++c)
      out[size_t(c)] = (1.0 - u) * keyValue(track, k, 0, c) + u * keyValue(track, k + 1, 0, c);
    return out;
  }
  // CUBICSPLINE: p(u) = h00 v_k + h10 span b_k + h01 v_k+1 + h11 span a_k+1, with v the
  // values, b the out-tangents, a the in-tangents (glTF 2.0, appendix C).
  const double u2 = u * u, u3 = u2 * u;
  const double h00 = 2.0 * u3 - 3.0 * u2 + 1.0, h10 = u3 - 2.0 * u2 + u;
  const double h01 = -2.0 * u3 + 3.0 * u2, h11 = u3 - u2;
  for (int c = 0; c < track.width; ++c)
    out[size_t(c)] = h00 * keyValue(track, k, 1, c) + h10 * span * keyValue(track, k, 2, c) +
                     h01 * keyValue(track, k + 1, 1, c) + h11 * span * keyValue(track, k + 1, 0, c);
  return track.quaternion ? normalised(out) : out;
}

}  // namespace gridrt
