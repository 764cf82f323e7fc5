// Keyframe interpolation as glTF 2.0 defines it for animation samplers: STEP, LINEAR
// (spherical linear along the shorter arc for rotations) and CUBICSPLINE (cubic Hermite
// with the file's in- and out-tangents, scaled by the key interval). Times before the
// first key and after the last clamp to the first and last key's value. Everything in
// double: a FLOAT key is exact in a double, and the pose is cast to float only per vertex,
// where the still pose is too.
#pragma once
#include <glm/glm.hpp>
#include <vector>

namespace gridrt {

enum class Interpolation { Step, Linear, CubicSpline };

// Above this cosine of the angle between two unit quaternions, slerp interpolates linearly
// and normalises (the glTF specification's threshold): sin(angle) in slerp's denominator
// is then below 0.032, and 0 for equal keys, which would divide zero by zero.
constexpr double kSlerpLinearAbove = 0.9995;

// One sampler's keys. `values` holds `width` numbers per key (3 for a translation, 4 for
// a rotation, the morph target count for weights); CUBICSPLINE holds three such groups
// per key: in-tangent, value, out-tangent. `times` are strictly increasing (the reader
// checks it; gltf_animation.h).
struct KeyframeTrack {
  Interpolation interpolation = Interpolation::Linear;
  bool quaternion = false;  // rotations (x, y, z, w): LINEAR slerps, CUBICSPLINE normalises
  int width = 1;
  std::vector<double> times;
  std::vector<double> values;
};

// The track's value at time t (width numbers).
std::vector<double> sampleTrack(const KeyframeTrack& track, double t);

// The unit quaternion a fraction u of the way from a to b along the shorter arc (b is
// negated when a . b < 0: q and -q are the same rotation). a and b are normalised first.
glm::dvec4 slerpShortArc(glm::dvec4 a, glm::dvec4 b, double u);

}  // namespace gridrt
