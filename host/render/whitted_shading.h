// The Whitted/Phong terms of a surface and a light (docs/gltf.md "Material mapping"), as pure
// functions the wavefront renderer calls per hit.
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <glm/glm.hpp>
#include <limits>

#include "scene.h"

namespace gridrt {

constexpr float kPi = 3.14159265358979f;

// How a material splits incoming light, derived from its glTF parameters.
struct SurfaceTerms {
  glm::vec3 diffuse;     // Lambert albedo: base * ((1 - metallic) * (1 - transmission)
                         //   + metallic * (1 - (1 - roughness)^2)): a metal's rough share
  glm::vec3 specular;    // Phong highlight colour: mix(0.04, base, metallic) * (1 - roughness)
  float phong_exponent;  // 2 / alpha^2 - 2 with alpha = roughness^2, in [1, 10000]
  glm::vec3 mirror;      // perfect-mirror reflectance: base * metallic * (1 - roughness)^2
  float transmission;    // share refracted (Fresnel-weighted) by a dielectric
};

SurfaceTerms surfaceTerms(const Material& m);
// The same with the base colour, metallic and roughness at a hit (textures, vertex
// colours) in place of the material's factors.
SurfaceTerms surfaceTerms(const Material& m, const glm::vec3& base_color, float metallic,
                          float roughness);

// Irradiance (per unit area facing the light) that `light` delivers at `p`, the unit
// direction towards the light and its distance (infinite for a directional light).
// Point/spot: intensity / d^2 (candela), the spot cone's smooth falloff as
// KHR_lights_punctual recommends, and a range window that goes smoothly to zero at the
// range: the square of the extension's recommended clamp(1 - (d/range)^4, 0, 1), as Unreal
// and Frostbite use it (the extension leaves the window to the renderer, asking only that
// it reach zero at the range); directional: intensity (lux). The one-hit definition:
// the shading loop computes it 16 hits at a time (computeLightLanes, hit_surfaces.h),
// bit for bit equal (tests/render/hit_surfaces_test.cpp).
glm::vec3 lightIrradiance(const Light& light, const glm::vec3& p, glm::vec3& to_light,
                          float& distance);

// Unpolarised Fresnel reflectance of a dielectric interface; cos_i > 0 on the incident
// side, eta = n_incident / n_transmitted. Returns 1 on total internal reflection.
float fresnelDielectric(float cos_i, float eta);

// Snell refraction of unit `d` through normal `n` (facing against d), eta = n1/n2.
// Returns false on total internal reflection.
bool refractDirection(const glm::vec3& d, const glm::vec3& n, float eta, glm::vec3& out);

// Ray origins for secondary rays, moved off the surface so they do not hit it again.
struct RayOffset {
  bool robust = true;     // scale-aware: bounded by the hit point's own rounding error
  float epsilon = 1e-4f;  // fixed world-space offset used when !robust
};

// The hit point p = o + t*d carries a rounding error of a few ulps of the largest
// coordinate involved (of p and of the ray origin o); the robust offset moves p along the
// normal by this many ulps of that magnitude, then one more ulp per axis. 16 already
// passes the re-intersection and shadow-acne tests at scales 1e-4..1e6; 64 is a 4x margin.
constexpr float kHitPointErrorUlps = 64.0f;
constexpr float kUlpOfOne = 0x1p-23f;  // float spacing at 1

// std::nextafter(x, +inf) when `up`, else std::nextafter(x, -inf), for a finite x:
// without branches, so that loops over lanes (plain_shading.cpp) vectorise.
inline float nextFiniteFloat(float x, bool up) {
  uint32_t bits;
  std::memcpy(&bits, &x, sizeof bits);
  bits = (x > 0.0f) == up ? bits + 1 : bits - 1;  // the magnitude one ulp up or down
  float moved;
  std::memcpy(&moved, &bits, sizeof moved);
  const float tiny = std::numeric_limits<float>::denorm_min();
  return x == 0.0f ? (up ? tiny : -tiny) : moved;
}

// The same for any x, without the library call for finite x (the shading loop takes three
// per secondary origin).
inline float nextFloat(float x, bool up) {
  if (!std::isfinite(x)) return std::nextafter(x, up ? INFINITY : -INFINITY);
  return nextFiniteFloat(x, up);
}

// How far a secondary ray's origin is moved off the surface of a hit point p found by a
// ray from ray_origin: the bound on p's rounding error (robust), or the fixed epsilon.
// Shadow rays also start their interval there (tmin): the same rounding may put p behind
// a neighbouring surface (the ceiling beside a wall point at a concave corner), which the
// ray would otherwise cross at once and call an occluder (tests/render/ray_offset_test.cpp).
inline float rayOffsetDistance(const glm::vec3& p, const glm::vec3& ray_origin,
                               const RayOffset& offset) {
  if (!offset.robust) return offset.epsilon;
  // Waechter & Binder's idea (Ray Tracing Gems, ch. 6) of an offset that scales with the
  // coordinates, bounded here by the error of p = o + t*d, which grows with |o| as well
  // as |p| (their fixed 1/65536 near the origin is too small for a far camera and too
  // large for a tiny scene: tests/render/ray_offset_test.cpp).
  float magnitude = 0.0f;
  for (int a = 0; a < 3; ++a)
    magnitude = std::max({magnitude, std::fabs(p[a]), std::fabs(ray_origin[a])});
  return kHitPointErrorUlps * kUlpOfOne * magnitude;
}

// p moved off the surface along `normal` (unit, on the side the new ray leaves towards) by
// `distance` (rayOffsetDistance), and with the robust offset one more ulp per axis.
// Inline: the shading loop calls it for every secondary origin, with the distance it
// computed once per hit.
inline glm::vec3 offsetRayOrigin(const glm::vec3& p, const glm::vec3& n, float distance,
                                 const RayOffset& offset) {
  glm::vec3 out = p + distance * n;
  if (!offset.robust) return out;
  for (int a = 0; a < 3; ++a)
    if (n[a] != 0.0f) out[a] = nextFloat(out[a], n[a] > 0.0f);
  return out;
}

// The same for a hit point p found by a ray from ray_origin.
inline glm::vec3 offsetRayOrigin(const glm::vec3& p, const glm::vec3& n,
                                 const glm::vec3& ray_origin, const RayOffset& offset) {
  return offsetRayOrigin(p, n, rayOffsetDistance(p, ray_origin, offset), offset);
}

}  // namespace gridrt
