// The glTF metallic-roughness BRDF (gltf_brdf.h) by the properties that pin it down: the
// GGX distribution integrates to 1 over the projected hemisphere, the BRDF is
// reciprocal, it never reflects more than it receives (a white furnace, integrated
// here), a black metal reflects nothing head on, and a mirror-smooth surface stays finite.
#include "gltf_brdf.h"

#include <gtest/gtest.h>

#include <cmath>

#include "default_scene.h"
#include "reference_intersector.h"
#include "renderer.h"
#include "run_command.h"

namespace gridrt {
namespace {

constexpr double kPi = 3.14159265358979323846;
// Midpoint sums of 20000 (and 400 x 400) steps: errors far below 1e-3 for these lobes.
constexpr double kIntegralTolerance = 1e-3;
// f(l, v) and f(v, l) are the same float operations in another order: a few ulps.
constexpr float kReciprocityTolerance = 1e-5f;

TEST(GltfBrdf, GgxDistributionIsNormalisedOverTheProjectedHemisphere) {
  for (float alpha : {0.1f, 0.5f, 1.0f}) {
    const int steps = 20000;
    double sum = 0.0;
    for (int i = 0; i < steps; ++i) {
      const double theta = (i + 0.5) / steps * kPi / 2;
      sum += ggxDistribution(float(std::cos(theta)), alpha) * std::cos(theta) * std::sin(theta);
    }
    EXPECT_NEAR(sum * (kPi / 2 / steps) * 2 * kPi, 1.0, kIntegralTolerance) << alpha;
  }
}

glm::vec3 direction(double theta, double phi) {
  return glm::vec3(float(std::sin(theta) * std::cos(phi)), float(std::sin(theta) * std::sin(phi)),
                   float(std::cos(theta)));
}

TEST(GltfBrdf, IsReciprocal) {
  const glm::vec3 n(0, 0, 1), a = direction(0.3, 0.2), b = direction(1.1, 2.5);
  for (float metallic : {0.0f, 1.0f})
    for (float roughness : {0.2f, 0.7f}) {
      const glm::vec3 ab = gltfBrdf({0.8f, 0.5f, 0.2f}, metallic, roughness, n, a, b);
      const glm::vec3 ba = gltfBrdf({0.8f, 0.5f, 0.2f}, metallic, roughness, n, b, a);
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(ab[c], ba[c], kReciprocityTolerance);
    }
}

// The reflected share of light from above, integrated over the viewing hemisphere.
double albedo(float metallic, float roughness, const glm::vec3& l) {
  const glm::vec3 n(0, 0, 1);
  const int steps = 400;
  double sum = 0.0;
  for (int i = 0; i < steps; ++i)
    for (int j = 0; j < steps; ++j) {
      const double theta = (i + 0.5) / steps * kPi / 2, phi = (j + 0.5) / steps * 2 * kPi;
      const glm::vec3 v = direction(theta, phi);
      sum += gltfBrdf(glm::vec3(1.0f), metallic, roughness, n, v, l).x * std::cos(theta) *
             std::sin(theta);
    }
  return sum * (kPi / 2 / steps) * (2 * kPi / steps);
}

TEST(GltfBrdf, AWhiteSurfaceNeverReflectsMoreThanItReceives) {
  const glm::vec3 l = direction(0.5, 0.0);
  for (float metallic : {0.0f, 1.0f})
    for (float roughness : {0.3f, 1.0f}) {
      const double a = albedo(metallic, roughness, l);
      EXPECT_LE(a, 1.0 + kIntegralTolerance) << metallic << " " << roughness;
      // Single scattering loses what bounces between microfacets: little of a smooth lobe.
      // (0.9993, 0.9728, 0.9891 and 0.3269 for the four here.)
      if (roughness < 0.5f) {
        EXPECT_GT(a, 0.9) << metallic << " " << roughness;
      }
    }
}

TEST(GltfBrdf, ABlackMetalReflectsNothingHeadOnAndABlackDielectricOnlyItsSpecularShare) {
  const glm::vec3 n(0, 0, 1), v = direction(0.4, 0.0), l = direction(0.4, kPi);
  // Head on, Schlick's term is F0 = the base colour: black. (At grazing angles it is not.)
  EXPECT_EQ(gltfBrdf(glm::vec3(0.0f), 1.0f, 0.5f, n, n, n), glm::vec3(0.0f));
  const glm::vec3 f = gltfBrdf(glm::vec3(0.0f), 0.0f, 0.5f, n, v, l);
  EXPECT_GT(f.x, 0.0f);
  EXPECT_EQ(f.x, f.y);  // grey: F0 = 0.04 in every channel
}

TEST(GltfBrdf, TransmissionTakesTheDiffuseLobe) {
  const glm::vec3 n(0, 0, 1), v = direction(0.4, 0.0), l = direction(0.9, 2.0);
  const glm::vec3 glass = gltfBrdf(glm::vec3(0.9f), 0.0f, 0.3f, n, v, l, 1.0f);
  const glm::vec3 black = gltfBrdf(glm::vec3(0.0f), 0.0f, 0.3f, n, v, l);
  EXPECT_EQ(glass, black);  // the specular lobe alone
  const glm::vec3 half = gltfBrdf(glm::vec3(0.9f), 0.0f, 0.3f, n, v, l, 0.5f);
  const glm::vec3 opaque = gltfBrdf(glm::vec3(0.9f), 0.0f, 0.3f, n, v, l);
  EXPECT_NEAR(half.x - black.x, 0.5f * (opaque.x - black.x), kReciprocityTolerance);
}

// The glTF 2.0 specification's Appendix B, in double. The microfacet lobe V D: GGX's D
// with chi+(n.h), Smith's separable G (each factor with chi+(h.x / n.x)) over 4 |n.l| |n.v|.
double microfacet(double roughness, const glm::dvec3& n, const glm::dvec3& v, const glm::dvec3& l) {
  const double a = roughness * roughness, a2 = a * a;
  const glm::dvec3 h = glm::normalize(l + v);
  const double nh = glm::dot(n, h), nl = glm::dot(n, l), nv = glm::dot(n, v);
  const double dd = nh * nh * (a2 - 1.0) + 1.0;
  const double d = nh > 0.0 ? a2 / (kPi * dd * dd) : 0.0;
  auto g1 = [&](double nx, double hx) {
    return hx / nx > 0.0
               ? 2.0 * std::fabs(nx) / (std::fabs(nx) + std::sqrt(a2 + (1 - a2) * nx * nx))
               : 0.0;
  };
  const double g = g1(nl, glm::dot(h, l)) * g1(nv, glm::dot(h, v));
  return g / (4.0 * std::fabs(nl) * std::fabs(nv)) * d;
}

// Schlick's (1 - |v.h|)^5.
double schlickWeight(const glm::dvec3& v, const glm::dvec3& l) {
  return std::pow(1.0 - std::fabs(glm::dot(v, glm::normalize(l + v))), 5.0);
}

// Appendix B's layered material: conductor_fresnel(base, V D) for the metal,
// fresnel_mix(ior 1.5, base / pi, V D) for the dielectric, mix(dielectric, metal, metallic).
glm::dvec3 appendixB(const glm::dvec3& base, double metallic, double roughness, const glm::dvec3& n,
                     const glm::dvec3& v, const glm::dvec3& l) {
  const double specular = microfacet(roughness, n, v, l), schlick = schlickWeight(v, l);
  const glm::dvec3 metal = specular * (base + (1.0 - base) * schlick);
  const double f0 = std::pow((1.0 - 1.5) / (1.0 + 1.5), 2.0);  // 0.04
  const double fr = f0 + (1.0 - f0) * schlick;
  const glm::dvec3 dielectric = (1.0 - fr) * (base / kPi) + fr * glm::dvec3(specular);
  return (1.0 - metallic) * dielectric + metallic * metal;
}

// Appendix B's single-lobe form for any metallic (its simplified implementation): c_diff =
// mix(base, 0, metallic), f0 = mix(0.04, base, metallic), F = f0 + (1 - f0) schlick, f =
// (1 - F) c_diff / pi + F V D. At metallic 0 and 1 it is the layered form.
glm::dvec3 appendixBSimplified(const glm::dvec3& base, double metallic, double roughness,
                               const glm::dvec3& n, const glm::dvec3& v, const glm::dvec3& l) {
  const double specular = microfacet(roughness, n, v, l), schlick = schlickWeight(v, l);
  const glm::dvec3 f0 = glm::dvec3(0.04) * (1.0 - metallic) + base * metallic;
  const glm::dvec3 f = f0 + (1.0 - f0) * schlick;
  return (1.0 - f) * (base * (1.0 - metallic)) / kPi + f * specular;
}

// The float BRDF against the double one: near the lobe's peak D's denominator (n.h)^2
// (alpha^2 - 1) + 1 cancels to alpha^2, where float keeps 1e-7 / alpha^2 of it relatively
// (2.5e-5 at roughness 0.3, the smoothest here).
constexpr double kAppendixBRelative = 1e-4;

TEST(GltfBrdf, IsAppendixBsBrdfAtEveryAngleAndRoughness) {
  const glm::vec3 n(0, 0, 1);
  const glm::dvec3 base(0.8, 0.5, 0.2);
  size_t checked = 0;
  for (const float metallic : {0.0f, 0.5f, 1.0f})
    for (const float roughness : {0.3f, 0.6f, 1.0f})
      for (const double theta_v : {0.0, 0.4, 1.0, 1.4})
        for (const double theta_l : {0.1, 0.4, 0.9, 1.45})
          for (const double phi : {0.0, 2.0, kPi}) {
            const glm::vec3 v = direction(theta_v, 0.0), l = direction(theta_l, phi);
            const glm::vec3 got = gltfBrdf(glm::vec3(base), metallic, roughness, n, v, l);
            const glm::dvec3 dn(n), dv(v), dl(l);
            const glm::dvec3 want = metallic == 0.5f
                                        ? appendixBSimplified(base, metallic, roughness, dn, dv, dl)
                                        : appendixB(base, metallic, roughness, dn, dv, dl);
            for (int c = 0; c < 3; ++c)
              EXPECT_NEAR(got[c], want[c], kAppendixBRelative * want[c])
                  << "metallic " << metallic << " roughness " << roughness << " view " << theta_v
                  << " light " << theta_l << " " << phi << " channel " << c;
            ++checked;
          }
  EXPECT_EQ(checked, 3u * 3u * 4u * 4u * 3u);
}

TEST(GltfBrdf, AMirrorSmoothSurfaceStaysFiniteInTheMirrorDirection) {
  const glm::vec3 n(0, 0, 1), v = direction(0.4, 0.0), l = direction(0.4, kPi);
  const glm::vec3 f = gltfBrdf(glm::vec3(1.0f), 1.0f, 0.0f, n, v, l);
  EXPECT_TRUE(std::isfinite(f.x) && f.x > 0.0f);
  EXPECT_EQ(gltfBrdf(glm::vec3(1.0f), 0.0f, 0.5f, n, -v, l), glm::vec3(0.0f));  // below
}

// --shading gltf: the renderer lights a hit with the BRDF times irradiance times n.l (a
// white quad under a directional light, seen head on), and Phong stays the default.
TEST(GltfBrdf, TheRendererShadesPunctualLightsWithItWhenAsked) {
  Scene scene;
  Material m;
  m.base_color = glm::vec3(0.7f);
  m.metallic = 0.0f;
  m.roughness = 0.6f;
  shapes::addRect(scene, {0, 0, 0}, {1, 0, 0}, {0, 1, 0}, shapes::addMaterial(scene, m));
  Light light;
  light.type = LightType::Directional;
  light.direction = -direction(0.6, 0.0);
  light.intensity = 2.0f;
  scene.lights.push_back(light);
  scene.has_lights = true;
  Camera camera;
  camera.orthographic = true;
  camera.xmag = camera.ymag = 0.5f;
  camera.world = shapes::lookAtWorld({0, 0, 3}, {0, 0, 0});
  ReferenceIntersector reference(scene);
  RenderSettings settings;
  settings.width = settings.height = 2;
  settings.max_depth = 0;
  auto render = [&](ShadingModel model) {
    settings.shading = model;
    Renderer renderer(scene, camera, reference, settings);
    Frame frame;
    renderer.render(frame);
    return frame.film.rgb[0];
  };
  const glm::vec3 n(0, 0, 1), l = direction(0.6, 0.0);
  const float direct = gltfBrdf(m.base_color, 0.0f, 0.6f, n, n, l).x * 2.0f * l.z;
  const float ambient = settings.ambient * surfaceTerms(m).diffuse.x;
  EXPECT_NEAR(render(ShadingModel::Gltf), ambient + direct, kReciprocityTolerance);
  EXPECT_NE(render(ShadingModel::Phong), render(ShadingModel::Gltf));
  EXPECT_EQ(RenderSettings{}.shading, ShadingModel::Phong);
}

TEST(GltfBrdf, AnUnknownShadingModelIsAUsageError) {
  const test::CommandResult r =
      test::runCommand({test::gridrtBinary(), "--shading", "pbr", "-o", test::tempPath("x.png")});
  EXPECT_EQ(r.exit_code, 2) << r.err;
}

}  // namespace
}  // namespace gridrt
