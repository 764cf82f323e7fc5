#include "whitted_shading.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

namespace gridrt {

SurfaceTerms surfaceTerms(const Material& m) {
  return surfaceTerms(m, m.base_color, m.metallic, m.roughness);
}

SurfaceTerms surfaceTerms(const Material& m, const glm::vec3& base_color, float metallic_factor,
                          float roughness_factor) {
  SurfaceTerms s;
  float transmission = std::clamp(m.transmission, 0.0f, 1.0f);
  float metallic = std::clamp(metallic_factor, 0.0f, 1.0f);
  float roughness = std::clamp(roughness_factor, 0.0f, 1.0f);
  // A metal reflects its base colour: the smooth share (1 - roughness)^2 as a perfect
  // mirror, the rest, scattered too widely for a mirror ray to stand for it, as a Lambert
  // lobe tinted by the base colour (a rough metal shows its colour, not black).
  const float smooth = (1.0f - roughness) * (1.0f - roughness);
  s.diffuse = base_color * ((1.0f - metallic) * (1.0f - transmission) + metallic * (1.0f - smooth));
  s.specular = glm::mix(glm::vec3(0.04f), base_color, metallic) * (1.0f - roughness);
  float alpha = roughness * roughness;
  s.phong_exponent =
      alpha > 0.0f ? std::clamp(2.0f / (alpha * alpha) - 2.0f, 1.0f, 10000.0f) : 10000.0f;
  s.mirror = base_color * metallic * (1.0f - roughness) * (1.0f - roughness);
  s.transmission = transmission * (1.0f - metallic);
  return s;
}

glm::vec3 lightIrradiance(const Light& light, const glm::vec3& p, glm::vec3& to_light,
                          float& distance) {
  if (light.type == LightType::Directional) {
    to_light = -glm::normalize(light.direction);
    distance = std::numeric_limits<float>::infinity();
    return light.color * light.intensity;
  }
  glm::vec3 v = light.position - p;
  float d2 = glm::dot(v, v);
  distance = std::sqrt(d2);
  if (!(distance > 0.0f)) {
    to_light = glm::vec3(0.0f, 1.0f, 0.0f);
    return glm::vec3(0.0f);
  }
  to_light = v / distance;
  float attenuation = 1.0f / d2;
  if (light.range > 0.0f) {
    float r = distance / light.range;
    attenuation *= std::pow(std::clamp(1.0f - r * r * r * r, 0.0f, 1.0f), 2.0f);
  }
  if (light.type == LightType::Spot) {
    float cos_outer = std::cos(light.outer_cone), cos_inner = std::cos(light.inner_cone);
    float cos_angle = glm::dot(-to_light, glm::normalize(light.direction));
    float scale = 1.0f / std::max(1e-3f, cos_inner - cos_outer);
    float t = std::clamp((cos_angle - cos_outer) * scale, 0.0f, 1.0f);
    attenuation *= t * t;
  }
  return light.color * light.intensity * attenuation;
}

float fresnelDielectric(float cos_i, float eta) {
  cos_i = std::clamp(cos_i, 0.0f, 1.0f);
  float sin2_t = eta * eta * (1.0f - cos_i * cos_i);
  if (sin2_t >= 1.0f) return 1.0f;
  float cos_t = std::sqrt(1.0f - sin2_t);
  float rs = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
  float rp = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
  return 0.5f * (rs * rs + rp * rp);
}

bool refractDirection(const glm::vec3& d, const glm::vec3& n, float eta, glm::vec3& out) {
  float cos_i = -glm::dot(d, n);
  float sin2_t = eta * eta * (1.0f - cos_i * cos_i);
  if (sin2_t >= 1.0f) return false;
  out = glm::normalize(eta * d + (eta * cos_i - std::sqrt(1.0f - sin2_t)) * n);
  return true;
}

}  // namespace gridrt
