// The glTF metallic-roughness BRDF for punctual lights, as the glTF 2.0 specification's
// Appendix B defines it: a Lambert lobe of the base colour's dielectric share, c_diff =
// base (1 - metallic), and a microfacet lobe with the GGX (Trowbridge-Reitz) distribution
// D, the separable Smith-GGX visibility V = G / (4 |n.l| |n.v|), and Schlick's Fresnel F
// with F0 = mix(0.04, base, metallic):  f = (1 - F) c_diff / pi + F D V,  alpha = roughness^2.
// The second local shading model beside Phong (--shading gltf); reflection and refraction
// rays stay the Whitted recursion's.
#pragma once
#include <glm/glm.hpp>

namespace gridrt {

// The local shading model of punctual lights.
enum class ShadingModel { Phong, Gltf };

// alpha = roughness^2 below this is raised to it: a perfectly smooth GGX lobe is a delta
// whose D is 0/0 where the light lies exactly in the mirror direction (the mirror ray
// carries that light); 1e-3 keeps D finite in float (tests/render/gltf_brdf_test.cpp).
constexpr float kMinGgxAlpha = 1e-3f;

// D(h) for n.h = n_dot_h and alpha (already raised to kMinGgxAlpha).
float ggxDistribution(float n_dot_h, float alpha);

// f(l, v) for unit normal n, unit directions v (towards the viewer) and l (towards the
// light), both on n's side; zero where either is not. transmission
// (KHR_materials_transmission) takes its share of the diffuse lobe: that light is refracted.
glm::vec3 gltfBrdf(const glm::vec3& base_color, float metallic, float roughness, const glm::vec3& n,
                   const glm::vec3& v, const glm::vec3& l, float transmission = 0.0f);

}  // namespace gridrt
