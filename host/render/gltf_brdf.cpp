#include "gltf_brdf.h"

#include <algorithm>
#include <cmath>

namespace gridrt {
namespace {

constexpr float kPi = 3.14159265358979f;

// Smith's G1 for GGX, 2 |n.x| / (|n.x| + sqrt(alpha^2 + (1 - alpha^2) (n.x)^2)).
float smithG1(float n_dot_x, float alpha2) {
  return 2.0f * n_dot_x / (n_dot_x + std::sqrt(alpha2 + (1.0f - alpha2) * n_dot_x * n_dot_x));
}

}  // namespace

float ggxDistribution(float n_dot_h, float alpha) {
  if (!(n_dot_h > 0.0f)) return 0.0f;
  const float alpha2 = alpha * alpha;
  const float d = n_dot_h * n_dot_h * (alpha2 - 1.0f) + 1.0f;
  return alpha2 / (kPi * d * d);
}

glm::vec3 gltfBrdf(const glm::vec3& base_color, float metallic, float roughness, const glm::vec3& n,
                   const glm::vec3& v, const glm::vec3& l, float transmission) {
  const float n_dot_l = glm::dot(n, l), n_dot_v = glm::dot(n, v);
  if (!(n_dot_l > 0.0f) || !(n_dot_v > 0.0f)) return glm::vec3(0.0f);
  metallic = std::clamp(metallic, 0.0f, 1.0f);
  roughness = std::clamp(roughness, 0.0f, 1.0f);
  const float alpha = std::max(roughness * roughness, kMinGgxAlpha);
  const float alpha2 = alpha * alpha;
  const glm::vec3 h = glm::normalize(l + v);
  const float v_dot_h = std::fabs(glm::dot(v, h));
  const glm::vec3 f0 = glm::mix(glm::vec3(0.04f), base_color, metallic);
  const float schlick = std::pow(1.0f - v_dot_h, 5.0f);
  const glm::vec3 fresnel = f0 + (glm::vec3(1.0f) - f0) * schlick;
  const float visibility =
      smithG1(n_dot_l, alpha2) * smithG1(n_dot_v, alpha2) / (4.0f * n_dot_l * n_dot_v);
  const glm::vec3 c_diff =
      base_color * ((1.0f - metallic) * (1.0f - std::clamp(transmission, 0.0f, 1.0f)));
  return (glm::vec3(1.0f) - fresnel) * c_diff / kPi +
         fresnel * (ggxDistribution(glm::dot(n, h), alpha) * visibility);
}

}  // namespace gridrt
