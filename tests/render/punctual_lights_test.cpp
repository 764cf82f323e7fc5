// The irradiance of point, spot and directional lights against KHR_lights_punctual, worked
// out here in double from the extension's text (not from the renderer's code): a point or
// spot light gives intensity / d^2 (candela), a directional light its intensity (lux); a
// spot's angular attenuation interpolates between the cosines of the inner and outer cone
// angles and is squared (the extension's reference code); a range window ends the light at
// its range. Both of the renderer's definitions are held against it: the one-hit
// lightIrradiance and the 16 lanes of computeLightLanes (hit_surfaces.h), at the cone's
// inner and outer edges, across the range's edge and beyond, and a rendered floor under a
// spot light through the plain lanes and through the one-hit loop.
#include <gtest/gtest.h>

#include <cfloat>
#include <cmath>
#include <glm/glm.hpp>
#include <string>
#include <vector>

#include "default_scene.h"
#include "hit_surfaces.h"
#include "reference_intersector.h"
#include "renderer.h"
#include "whitted_shading.h"

namespace gridrt {
namespace {

constexpr double kPiD = 3.14159265358979323846;

// Float irradiance against the double one: d^2, the window and the cone each round by a
// few ulps of float, so 1e-5 of the value.
constexpr double kIrradianceRelative = 1e-5;
// The cone's cosine (a float dot product of float unit vectors) is off by a few ulps of 1;
// times the cone's slope 2 t / (cos_inner - cos_outer) that is the error near its edges.
constexpr double kConeCosineError = 1e-6;
// 1 - (d / range)^4 loses a few ulps of 1 when d nears the range; times the window's
// slope 2 w that is the error near the range's edge.
constexpr double kWindowError = 1e-6;
// A unit direction (and a distance, relatively) in float against the double one: a few ulps.
constexpr double kDirectionTolerance = 1e-6;

// What the extension asks of a light at a point, in double.
struct Expected {
  glm::dvec3 irradiance{0.0};
  glm::dvec3 to_light{0.0};
  double distance = 0.0;
  double tolerance = 0.0;  // per channel, from the tolerances above
};

// The range window. The extension recommends clamp(1 - (d / range)^4, 0, 1) itself; the
// renderer squares it, as Karis ("Real Shading in Unreal Engine 4", 2013) and Lagarde and
// de Rousiers ("Moving Frostbite to PBR", 2014) do, so that it meets zero with zero slope
// (the extension allows "some non-quadratic falloff near the edge of the range"). Zero at
// the range and beyond, as the extension requires.
double rangeWindow(double distance, double range) {
  if (range <= 0.0) return 1.0;  // undefined range: the inverse square law alone
  const double r = distance / range;
  const double w = std::min(std::max(1.0 - r * r * r * r, 0.0), 1.0);
  return w * w;
}

// The spot's angular attenuation: the cosine of the angle to the spot's axis mapped
// linearly from cos(outer) (0) to cos(inner) (1), clamped, then squared (the extension's
// reference code, lightAngleScale and lightAngleOffset; its max(0.001, ...) kept).
double coneAttenuation(double cos_angle, double inner, double outer, double* slope) {
  const double scale = 1.0 / std::max(0.001, std::cos(inner) - std::cos(outer));
  const double t = std::min(std::max((cos_angle - std::cos(outer)) * scale, 0.0), 1.0);
  *slope = 2.0 * t * scale;
  return t * t;
}

Expected expected(const Light& light, const glm::vec3& point) {
  Expected e;
  const glm::dvec3 colour_intensity = glm::dvec3(light.color) * double(light.intensity);
  if (light.type == LightType::Directional) {
    e.to_light = -glm::normalize(glm::dvec3(light.direction));
    e.distance = INFINITY;
    e.irradiance = colour_intensity;
    e.tolerance = kIrradianceRelative * std::max({e.irradiance.x, e.irradiance.y, e.irradiance.z});
    return e;
  }
  const glm::dvec3 v = glm::dvec3(light.position) - glm::dvec3(point);
  e.distance = glm::length(v);
  e.to_light = v / e.distance;
  const glm::dvec3 inverse_square = colour_intensity / (e.distance * e.distance);
  double attenuation = rangeWindow(e.distance, light.range);
  // An error delta in w = 1 - (d / range)^4 moves w^2 by up to 2 w delta + delta^2; the
  // cone's t the same way.
  const double w = std::sqrt(attenuation);
  double absolute = light.range > 0.0f ? 2.0 * w * kWindowError + kWindowError * kWindowError : 0.0;
  if (light.type == LightType::Spot) {
    double slope = 0.0;
    const double cone =
        coneAttenuation(glm::dot(-e.to_light, glm::normalize(glm::dvec3(light.direction))),
                        light.inner_cone, light.outer_cone, &slope);
    const double scale = 1.0 / std::max(0.001, std::cos(double(light.inner_cone)) -
                                                   std::cos(double(light.outer_cone)));
    const double t_error = scale * kConeCosineError;
    absolute = absolute * (cone + slope * kConeCosineError + t_error * t_error) +
               attenuation * (slope * kConeCosineError + t_error * t_error);
    attenuation *= cone;
  }
  e.irradiance = inverse_square * attenuation;
  const double largest = std::max({inverse_square.x, inverse_square.y, inverse_square.z});
  e.tolerance = kIrradianceRelative * largest * attenuation + largest * absolute;
  return e;
}

// A point at `distance` from a spot's position, `angle` (radians) off its axis.
glm::vec3 offAxis(const Light& light, double angle, double distance) {
  const glm::dvec3 axis = glm::normalize(glm::dvec3(light.direction));
  const glm::dvec3 side = glm::normalize(glm::cross(axis, glm::dvec3(0.3, 0.9, 0.1)));
  return glm::vec3(glm::dvec3(light.position) +
                   distance * (std::cos(angle) * axis + std::sin(angle) * side));
}

Light spotLight() {
  Light spot;
  spot.type = LightType::Spot;
  spot.position = {1.0f, 2.5f, -0.5f};
  spot.direction = glm::normalize(glm::vec3(0.2f, -1.0f, 0.3f));
  spot.color = {1.0f, 0.6f, 0.3f};
  spot.intensity = 40.0f;
  spot.inner_cone = 0.3f;
  spot.outer_cone = 0.6f;
  return spot;
}

// The points each light is checked at: for a spot, angles at and around the cone's edges
// (float's own angles: the edges as the light's floats hold them) and past the outer one;
// distances across the range's edge and beyond it.
struct Case {
  Light light;
  int light_id;  // cases of one light are consecutive
  glm::vec3 point;
  std::string what;
};

std::vector<Case> cases() {
  std::vector<Case> out;
  Light point;
  point.position = {-0.5f, 3.0f, 1.5f};
  point.color = {0.9f, 1.0f, 0.5f};
  point.intensity = 7.0f;
  for (double d : {0.05, 0.7, 2.0, 9.5, 130.0})
    out.push_back({point, 0,
                   point.position - glm::vec3(glm::normalize(glm::dvec3(0.3, 1, -0.2)) * d),
                   "point at " + std::to_string(d)});
  Light ranged = point;
  ranged.range = 4.0f;
  for (double d : {0.3, 1.0, 2.0, 3.0, 3.6, 3.9, 3.99, 3.999, 4.0, 4.001, 4.5, 40.0})
    out.push_back({ranged, 1,
                   ranged.position - glm::vec3(glm::normalize(glm::dvec3(-0.6, 1, 0.1)) * d),
                   "point with range 4 at " + std::to_string(d)});
  const Light spot = spotLight();
  const double inner = spot.inner_cone, outer = spot.outer_cone;
  for (double angle :
       {0.0, 0.1, inner - 1e-3, inner, inner + 1e-3, inner + 0.05, 0.45, 0.5, outer - 0.05,
        outer - 1e-3, outer - 1e-4, outer, outer + 1e-3, 0.8, 1.5, 2.5})
    for (double d : {0.5, 3.0})
      out.push_back({spot, 2, offAxis(spot, angle, d),
                     "spot at angle " + std::to_string(angle) + ", distance " + std::to_string(d)});
  Light ranged_spot = spot;
  ranged_spot.range = 5.0f;
  for (double d : {1.0, 4.0, 4.9, 4.99, 5.0, 6.0})
    for (double angle : {0.0, 0.45})
      out.push_back({ranged_spot, 3, offAxis(ranged_spot, angle, d),
                     "spot with range 5 at angle " + std::to_string(angle) + ", distance " +
                         std::to_string(d)});
  Light narrow = spot;  // inner and outer a hair apart: the 0.001 floor of the cone's scale
  narrow.inner_cone = 0.4f;
  narrow.outer_cone = 0.40001f;
  for (double angle : {0.39, 0.3995, 0.4, 0.40002, 0.41})
    out.push_back(
        {narrow, 4, offAxis(narrow, angle, 2.0), "narrow spot at angle " + std::to_string(angle)});
  Light sun;
  sun.type = LightType::Directional;
  sun.direction = glm::normalize(glm::vec3(-0.3f, -1.0f, 0.4f));
  sun.color = {1.0f, 0.95f, 0.8f};
  sun.intensity = 3.5f;
  for (float x : {0.0f, 100.0f, -1e4f}) out.push_back({sun, 5, {x, 1.0f, 2.0f}, "directional"});
  return out;
}

void expectIrradiance(const Expected& want, const glm::vec3& e, const std::string& where) {
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(e[c], want.irradiance[c], want.tolerance) << where;
}

TEST(PunctualLights, OneHitIrradianceIsTheExtensionsAtTheConesAndRangesEdges) {
  size_t cut_off = 0, partial = 0;
  for (const Case& c : cases()) {
    const Expected want = expected(c.light, c.point);
    glm::vec3 to;
    float distance = 0.0f;
    const glm::vec3 e = lightIrradiance(c.light, c.point, to, distance);
    expectIrradiance(want, e, "lightIrradiance, " + c.what);
    for (int a = 0; a < 3; ++a) EXPECT_NEAR(to[a], want.to_light[a], kDirectionTolerance) << c.what;
    if (std::isfinite(want.distance))
      EXPECT_NEAR(distance, want.distance, kDirectionTolerance * want.distance) << c.what;
    else
      EXPECT_EQ(distance, INFINITY) << c.what;
    cut_off += want.irradiance == glm::dvec3(0.0);
    // Inside the cone's band or the range's window: neither 0 nor the full falloff.
    const double full = double(c.light.intensity) /
                        (std::isfinite(want.distance) ? want.distance * want.distance : 1.0);
    partial += want.irradiance.x > 0.0 && want.irradiance.x < 0.99 * full * c.light.color.x;
  }
  EXPECT_GT(cut_off, 10u);  // beyond a cone or a range
  EXPECT_GT(partial, 20u);
}

TEST(PunctualLights, LanesIrradianceIsTheExtensionsAtTheConesAndRangesEdges) {
  const std::vector<Case> all = cases();
  size_t lit = 0;
  for (size_t first = 0; first < all.size();) {
    // Lanes of one light at a time: up to 16 of its cases (consecutive in cases()), the
    // lanes past them copies of the first.
    std::vector<const Case*> block;
    for (; first < all.size() && block.size() < size_t(kSurfaceLanes) &&
           (block.empty() || all[first].light_id == block[0]->light_id);
         ++first)
      block.push_back(&all[first]);
    SurfaceLanes s{};
    for (int k = 0; k < kSurfaceLanes; ++k) {
      const Case& c = *block[size_t(k) < block.size() ? size_t(k) : 0];
      s.px[k] = c.point.x, s.py[k] = c.point.y, s.pz[k] = c.point.z;
      // Both normals facing the light: lit wherever it gives irradiance.
      const glm::vec3 n(glm::normalize(expected(c.light, c.point).to_light));
      s.nx[k] = s.gx[k] = n.x, s.ny[k] = s.gy[k] = n.y, s.nz[k] = s.gz[k] = n.z;
    }
    LightLanes out;
    computeLightLanes(block[0]->light, s, out);
    for (size_t k = 0; k < block.size(); ++k) {
      const Expected want = expected(block[k]->light, block[k]->point);
      const std::string where = "computeLightLanes, " + block[k]->what;
      expectIrradiance(want, glm::vec3(out.ex[k], out.ey[k], out.ez[k]), where);
      EXPECT_NEAR(out.lx[k], want.to_light.x, kDirectionTolerance) << where;
      EXPECT_NEAR(out.ly[k], want.to_light.y, kDirectionTolerance) << where;
      EXPECT_NEAR(out.lz[k], want.to_light.z, kDirectionTolerance) << where;
      EXPECT_NEAR(out.cos_theta[k], 1.0, kDirectionTolerance) << where;
      // Lit where it gives light; at an edge (within the tolerance of 0) either is right.
      if (std::max({want.irradiance.x, want.irradiance.y, want.irradiance.z}) > want.tolerance ||
          want.tolerance == 0.0) {
        EXPECT_EQ(bool(out.lit[k]), want.irradiance != glm::dvec3(0.0)) << where;
      }
      lit += out.lit[k];
    }
  }
  EXPECT_GT(lit, 40u);
}

// A grey Lambert floor (no highlight) under a spot light pointing straight down, with a
// range that ends between the cone's inner and outer edges; no ambient. Every pixel is
// base / pi * E * cos_theta of its point (radiance of a Lambert surface), or 0 where the
// cone or the range cuts the light off; through the plain lanes and the one-hit loop.
TEST(PunctualLights, AFloorUnderASpotIsLambertTimesTheExtensionsFalloff) {
  Scene scene;
  Material grey;
  grey.base_color = glm::vec3(0.5f, 0.4f, 0.3f);
  grey.roughness = 1.0f;  // no highlight: specular (1 - roughness) = 0
  shapes::addRect(scene, {0, 0, 0}, {3, 0, 0}, {0, 0, -3}, shapes::addMaterial(scene, grey));
  Light spot;
  spot.type = LightType::Spot;
  spot.position = {0.1f, 2.0f, -0.2f};
  spot.direction = {0.0f, -1.0f, 0.0f};
  spot.intensity = 5.0f;
  spot.inner_cone = 0.35f;  // on the floor at a radius of 0.73
  spot.outer_cone = 0.7f;   // 1.69
  spot.range = 2.6f;        // 1.66
  scene.lights = {spot};
  scene.has_lights = true;
  Camera camera;
  camera.orthographic = true;
  camera.xmag = camera.ymag = 2.0f;
  camera.world = shapes::lookAtWorld({0, 5, 0}, {0, 0, 0}, {0, 0, -1});
  ReferenceIntersector reference(scene);
  RenderSettings settings;
  settings.width = settings.height = 48;
  settings.ambient = 0.0f;
  settings.max_depth = 0;
  for (const bool plain_lanes : {true, false}) {
    settings.plain_lanes = plain_lanes;
    Renderer renderer(scene, camera, reference, settings);
    Frame frame;
    renderer.render(frame);
    size_t dark = 0, band = 0, inner = 0;
    for (int j = 0; j < settings.height; ++j)
      for (int i = 0; i < settings.width; ++i) {
        // The pixel's centre on the floor: the orthographic camera looks down -Y, its +X
        // world +X, its +Y world -Z.
        const float x = -2.0f + 4.0f * (i + 0.5f) / settings.width;
        const float z = -(2.0f - 4.0f * (j + 0.5f) / settings.height);
        const glm::vec3 p(x, 0.0f, z);
        const Expected want = expected(spot, p);
        const double cos_theta = want.to_light.y;  // the floor's normal is +Y
        const size_t at = 3 * (size_t(j) * settings.width + i);
        for (int c = 0; c < 3; ++c) {
          const double radiance = grey.base_color[c] / kPiD * want.irradiance[c] * cos_theta;
          // The irradiance's own tolerance, through the Lambert term.
          const double tolerance = grey.base_color[c] / kPiD * cos_theta * want.tolerance;
          EXPECT_NEAR(frame.film.rgb[at + c], radiance, tolerance)
              << (plain_lanes ? "plain lanes" : "one-hit loop") << ", pixel " << i << "," << j;
        }
        const double rho = std::hypot(x - spot.position.x, z - spot.position.z);
        dark += want.irradiance.x == 0.0;
        band += rho > 0.8 && rho < 1.6;
        inner += rho < 0.7;
      }
    EXPECT_GT(dark, 500u);
    EXPECT_GT(band, 300u);
    EXPECT_GT(inner, 200u);
  }
}

}  // namespace
}  // namespace gridrt
