// The Whitted/Phong terms of a surface and a light (README "Material mapping"), as pure
// functions the wavefront renderer calls per hit.
#pragma once
#include <glm/glm.hpp>

#include "scene.h"

namespace gridrt {

// How a material splits incoming light, derived from its glTF parameters.
struct SurfaceTerms {
  glm::vec3 diffuse;      // Lambert albedo: base * (1 - metallic) * (1 - transmission)
  glm::vec3 specular;     // Phong highlight colour: mix(0.04, base, metallic) * (1 - roughness)
  float phong_exponent;   // 2 / alpha^2 - 2 with alpha = roughness^2, in [1, 10000]
  glm::vec3 mirror;       // perfect-mirror reflectance: base * metallic * (1 - roughness)^2
  float transmission;     // share refracted (Fresnel-weighted) by a dielectric
};

SurfaceTerms surfaceTerms(const Material& m);

// Irradiance (per unit area facing the light) that `light` delivers at `p`, the unit
// direction towards the light and its distance (infinite for a directional light).
// Point/spot: intensity / d^2 (candela), spot cone smooth falloff and range window as
// KHR_lights_punctual recommends; directional: intensity (lux).
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

// p moved off the surface along `normal` (unit, on the side the new ray leaves towards);
// ray_origin is the origin of the ray that found p.
glm::vec3 offsetRayOrigin(const glm::vec3& p, const glm::vec3& normal,
                          const glm::vec3& ray_origin, const RayOffset& offset);

}  // namespace gridrt
