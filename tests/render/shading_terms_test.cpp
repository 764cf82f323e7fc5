// The Whitted terms of docs/gltf.md's material table against values worked out here, in
// double, from the physics and the table (never from the renderer's code): the Fresnel
// equations in their angle form and Snell's law built from angles, for the one-hit
// functions and for the lanes that spawn the plain path's rays; and rendered pixels, through
// the plain lanes and the one-hit loop, of the Lambert and classic Phong terms under a
// point light, the ambient term, a tinted and a rough mirror, and a tinted glass slab.
#include <gtest/gtest.h>

#include <cmath>
#include <glm/glm.hpp>
#include <string>
#include <vector>

#include "camera_rays.h"
#include "default_scene.h"
#include "plain_shading.h"
#include "reference_intersector.h"
#include "renderer.h"
#include "whitted_shading.h"

namespace gridrt {
namespace {

constexpr double kPiD = 3.14159265358979323846;

// A reflectance or a direction component in float against its double: a few ulps of 1.
constexpr double kUnitTolerance = 2e-6;
// A rendered pixel against its double value: the shading's float operations, 1e-5 of it.
constexpr double kPixelRelative = 1e-5;
// The renderer's hit point (its intersector's float t) and the one worked out here differ
// by a few ulps: a Phong highlight of exponent n moves by n times as much, relatively.
constexpr double kHitPointRelative = 2e-6;

// Unpolarised Fresnel reflectance from the angles of incidence and transmission (Fresnel's
// sine and tangent laws), n1 on the incident side; 1 beyond the critical angle.
double fresnelOracle(double theta_i, double n1, double n2) {
  const double sin_t = n1 / n2 * std::sin(theta_i);
  if (sin_t >= 1.0) return 1.0;
  const double theta_t = std::asin(sin_t);
  if (theta_i < 1e-9) {  // normal incidence: the limit of both laws
    const double r = (n1 - n2) / (n1 + n2);
    return r * r;
  }
  const double rs = std::sin(theta_i - theta_t) / std::sin(theta_i + theta_t);
  const double rp = std::tan(theta_i - theta_t) / std::tan(theta_i + theta_t);
  return 0.5 * (rs * rs + rp * rp);
}

// The refracted direction for unit d arriving at angle theta_i on a surface of normal n
// (facing d): in the plane of d and n, theta_t = asin(n1/n2 sin theta_i) from -n.
glm::dvec3 refractedOracle(const glm::dvec3& d, const glm::dvec3& n, double n1, double n2) {
  const double cos_i = -glm::dot(d, n);
  const glm::dvec3 along = d + cos_i * n;  // d's part in the surface
  const double sin_i = glm::length(along);
  if (sin_i < 1e-12) return d;
  const double theta_t = std::asin(n1 / n2 * sin_i);
  return -std::cos(theta_t) * n + std::sin(theta_t) * (along / sin_i);
}

// Incidence angles (degrees) from normal to grazing, through glass's critical 41.8.
const double kAngles[] = {0.0, 5.0, 20.0, 35.0, 41.0, 41.9, 50.0, 60.0, 75.0, 85.0, 89.0};

TEST(ShadingTerms, FresnelIsTheAngleFormOfFresnelsEquationsBothWays) {
  size_t total_internal = 0;
  for (const double ior : {1.33, 1.5, 2.4})
    for (const double degrees : kAngles) {
      const double theta = degrees * kPiD / 180.0;
      const float cos_i = float(std::cos(theta));
      const std::string where = "ior " + std::to_string(ior) + " at " + std::to_string(degrees);
      EXPECT_NEAR(fresnelDielectric(cos_i, float(1.0 / ior)), fresnelOracle(theta, 1.0, ior),
                  kUnitTolerance)
          << "entering, " << where;
      const double leaving = fresnelOracle(theta, ior, 1.0);
      total_internal += leaving == 1.0;
      EXPECT_NEAR(fresnelDielectric(cos_i, float(ior)), leaving, kUnitTolerance)
          << "leaving, " << where;
    }
  EXPECT_GT(total_internal, 10u);
}

TEST(ShadingTerms, RefractionIsSnellsLawBuiltFromAngles) {
  const glm::dvec3 n = glm::normalize(glm::dvec3(0.2, 1.0, -0.3));
  const glm::dvec3 side = glm::normalize(glm::cross(n, glm::dvec3(1.0, 0.0, 0.0)));
  for (const double ior : {1.33, 1.5, 2.4})
    for (const double degrees : kAngles) {
      const double theta = degrees * kPiD / 180.0;
      const glm::dvec3 d = -std::cos(theta) * n + std::sin(theta) * side;
      for (const bool entering : {true, false}) {
        const double n1 = entering ? 1.0 : ior, n2 = entering ? ior : 1.0;
        glm::vec3 out;
        const bool refracted = refractDirection(glm::vec3(d), glm::vec3(n), float(n1 / n2), out);
        const bool want = n1 / n2 * std::sin(theta) < 1.0;
        const std::string where = std::to_string(degrees) + " degrees, " +
                                  (entering ? "entering" : "leaving") + " ior " +
                                  std::to_string(ior);
        ASSERT_EQ(refracted, want) << where;
        if (!want) continue;
        const glm::dvec3 t = refractedOracle(d, n, n1, n2);
        for (int a = 0; a < 3; ++a) EXPECT_NEAR(out[a], t[a], kUnitTolerance) << where;
      }
    }
}

// The plain path's spawned rays, 16 hits at a time, for a tinted glass (transmission 1)
// hit from outside and from inside: the refracted ray's direction is Snell's, its weight
// base * (1 - F), and the reflected ray's weight F (the transmission's reflected share,
// untinted) or 1 past the critical angle, with F the angle form of Fresnel's equations.
TEST(ShadingTerms, SpawnLanesRefractAndReflectAsSnellAndFresnelSay) {
  PlainMaterial glass;
  glass.plain = 1;
  glass.spawning = 1;
  glass.transmission = 1.0f;
  glass.ior = 1.5f;
  glass.base_color = {1.0f, 0.8f, 0.6f};
  const glm::dvec3 n(0.0, 1.0, 0.0), side(1.0, 0.0, 0.0);
  size_t checked = 0, total_internal = 0;
  for (const bool inside : {false, true}) {
    SurfaceLanes s{};
    PlainLanes p{};
    const int count = int(std::size(kAngles));
    for (int k = 0; k < kSurfaceLanes; ++k) {
      const double theta = kAngles[k < count ? k : 0] * kPiD / 180.0;
      const glm::vec3 d(-std::cos(theta) * n + std::sin(theta) * side);
      s.px[k] = 0.1f * k, s.py[k] = 0.0f, s.pz[k] = 0.0f;
      s.ox[k] = s.px[k] - d.x, s.oy[k] = -d.y, s.oz[k] = -d.z;
      s.dx[k] = d.x, s.dy[k] = d.y, s.dz[k] = d.z;
      s.nx[k] = s.gx[k] = 0.0f, s.ny[k] = s.gy[k] = 1.0f, s.nz[k] = s.gz[k] = 0.0f;
      s.backface[k] = inside;
      p.wr[k] = p.wg[k] = p.wb[k] = 1.0f;
      p.material[k] = 0;
    }
    computePlainLanes(s, &glass, 0.0f, RayOffset{}, p);
    SpawnLanes out;
    computeSpawnLanes(s, &glass, RayOffset{}, 0.0f, p, out);
    for (int k = 0; k < count; ++k) {
      const double theta = kAngles[k] * kPiD / 180.0;
      const double n1 = inside ? 1.5 : 1.0, n2 = inside ? 1.0 : 1.5;
      const std::string where =
          std::to_string(kAngles[k]) + " degrees from " + (inside ? "inside" : "outside");
      ASSERT_TRUE(p.plain[k]) << where;
      const double f = fresnelOracle(theta, n1, n2);
      ASSERT_EQ(bool(out.refract[k]), f < 1.0) << where;
      ASSERT_TRUE(out.reflect[k]) << where;
      EXPECT_NEAR(out.fwr[k], f, kUnitTolerance) << where;
      EXPECT_NEAR(out.fwb[k], f, kUnitTolerance) << where;
      total_internal += f == 1.0;
      if (f == 1.0) continue;
      const glm::dvec3 t = refractedOracle(glm::dvec3(s.dx[k], s.dy[k], s.dz[k]), n, n1, n2);
      EXPECT_NEAR(out.rdx[k], t.x, kUnitTolerance) << where;
      EXPECT_NEAR(out.rdy[k], t.y, kUnitTolerance) << where;
      EXPECT_NEAR(out.rdz[k], t.z, kUnitTolerance) << where;
      EXPECT_NEAR(out.rwr[k], 1.0 * (1.0 - f), kUnitTolerance) << where;
      EXPECT_NEAR(out.rwg[k], 0.8 * (1.0 - f), kUnitTolerance) << where;
      EXPECT_NEAR(out.rwb[k], 0.6 * (1.0 - f), kUnitTolerance) << where;
      ++checked;
    }
  }
  EXPECT_GT(checked, 15u);
  EXPECT_GT(total_internal, 3u);
}

// ---- Rendered pixels ------------------------------------------------------------------

glm::dvec3 pixelOf(const Frame& frame, int i, int j) {
  const size_t at = 3 * (size_t(j) * frame.film.width + i);
  return {frame.film.rgb[at], frame.film.rgb[at + 1], frame.film.rgb[at + 2]};
}

// Renders `scene` through the exact reference intersector, with the plain lanes or the
// one-hit loop.
Frame render(const Scene& scene, const Camera& camera, RenderSettings settings, bool plain) {
  ReferenceIntersector reference(scene);
  settings.plain_lanes = plain;
  Renderer renderer(scene, camera, reference, settings);
  Frame frame;
  renderer.render(frame);
  return frame;
}

const char* pathName(bool plain) { return plain ? "plain lanes" : "one-hit loop"; }

// An orthographic camera at `eye` looking at the origin, `half` across from its centre to
// each edge, its image's up `up`.
Camera orthographic(const glm::vec3& eye, const glm::vec3& up, float half) {
  Camera camera;
  camera.orthographic = true;
  camera.xmag = camera.ymag = half;
  camera.world = shapes::lookAtWorld(eye, {0, 0, 0}, up);
  return camera;
}

// A half-metal floor under a point light, seen in perspective: each pixel is the table's
// Lambert term kd / pi * E cos_theta plus its classic Phong highlight ks E (R.V)^n, with
// kd = base ((1 - m) + m (1 - (1 - r)^2)), ks = mix(0.04, base, m) (1 - r), n = 2 / alpha^2
// - 2, alpha = r^2, E = I / d^2, R the light's direction mirrored about the normal and V
// the way back to the eye; no ambient, no reflection ray.
TEST(ShadingTerms, AFloorUnderAPointLightIsLambertPlusClassicPhong) {
  Scene scene;
  Material m;
  m.base_color = {0.9f, 0.5f, 0.2f};
  m.metallic = 0.5f;
  m.roughness = 0.3f;
  shapes::addRect(scene, {0, 0, 0}, {3, 0, 0}, {0, 0, -3}, shapes::addMaterial(scene, m));
  Light light;
  light.position = {0.3f, 1.5f, 0.2f};
  light.intensity = 4.0f;
  light.color = {1.0f, 0.9f, 0.7f};
  scene.lights = {light};
  scene.has_lights = true;
  const Camera camera = lookAtCamera({0.0f, 2.0f, 2.5f}, {0.0f, 0.0f, 0.0f}, 0.9f);
  RenderSettings settings;
  settings.width = 64;
  settings.height = 48;
  settings.ambient = 0.0f;
  settings.max_depth = 0;
  const double r = 0.3, metal = 0.5, alpha = r * r, exponent = 2.0 / (alpha * alpha) - 2.0;
  const glm::dvec3 base(m.base_color);
  const glm::dvec3 kd = base * ((1.0 - metal) + metal * (1.0 - (1.0 - r) * (1.0 - r)));
  const glm::dvec3 ks = (glm::dvec3(0.04) * (1.0 - metal) + base * metal) * (1.0 - r);
  for (const bool plain : {true, false}) {
    const Frame frame = render(scene, camera, settings, plain);
    size_t highlit = 0, checked = 0;
    for (int j = 0; j < settings.height; ++j)
      for (int i = 0; i < settings.width; ++i) {
        const GrRay ray = cameraRay(camera, settings.width, settings.height, i, j, 0.5f, 0.5f);
        const glm::dvec3 o(ray.ox, ray.oy, ray.oz), d(ray.dx, ray.dy, ray.dz);
        const double t = -o.y / d.y;
        const glm::dvec3 p = o + t * d;
        if (!(t > 0.0) || std::fabs(p.x) > 2.95 || std::fabs(p.z) > 2.95) continue;
        const glm::dvec3 n(0.0, 1.0, 0.0), to = glm::dvec3(light.position) - p;
        const double d2 = glm::dot(to, to);
        const glm::dvec3 l = to / std::sqrt(d2), v = -glm::normalize(d);
        const glm::dvec3 e = glm::dvec3(light.color) * double(light.intensity) / d2;
        const double rv = std::max(0.0, glm::dot(2.0 * glm::dot(n, l) * n - l, v));
        const double highlight = std::pow(rv, exponent);
        const glm::dvec3 want = kd / kPiD * e * l.y + ks * e * highlight;
        const glm::dvec3 got = pixelOf(frame, i, j);
        for (int c = 0; c < 3; ++c) {
          const double tolerance =
              kPixelRelative * want[c] + exponent * kHitPointRelative * ks[c] * e[c] * highlight;
          EXPECT_NEAR(got[c], want[c], tolerance)
              << pathName(plain) << ", pixel " << i << "," << j << " channel " << c;
        }
        highlit += ks.x * e.x * highlight > 0.1 * kd.x / kPiD * e.x * l.y;
        ++checked;
      }
    EXPECT_GT(checked, 2000u);
    EXPECT_GT(highlit, 10u) << "the highlight should show";
  }
}

// No light: a pixel is the ambient factor times the table's diffuse albedo, for a
// dielectric, a rough half metal and a half-transmitting dielectric.
TEST(ShadingTerms, WithoutLightsAPixelIsAmbientTimesTheDiffuseAlbedo) {
  struct Kind {
    float metallic, roughness, transmission;
  };
  for (const Kind kind : {Kind{0.0f, 0.5f, 0.0f}, Kind{0.5f, 0.6f, 0.0f}, Kind{0.0f, 1.0f, 0.5f}}) {
    Scene scene;
    Material m;
    m.base_color = {0.3f, 0.6f, 0.9f};
    m.metallic = kind.metallic;
    m.roughness = kind.roughness;
    m.transmission = kind.transmission;
    shapes::addRect(scene, {0, 0, 0}, {3, 0, 0}, {0, 0, -3}, shapes::addMaterial(scene, m));
    scene.has_lights = true;  // none
    const Camera camera = orthographic({0, 5, 0}, {0, 0, -1}, 1.0f);
    RenderSettings settings;
    settings.width = settings.height = 8;
    settings.ambient = 0.2f;
    settings.max_depth = 0;
    const double metal = kind.metallic, r = kind.roughness;
    const double share =
        (1.0 - metal) * (1.0 - kind.transmission) + metal * (1.0 - (1.0 - r) * (1.0 - r));
    for (const bool plain : {true, false}) {
      const glm::dvec3 got = pixelOf(render(scene, camera, settings, plain), 3, 4);
      for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(got[c], 0.2 * m.base_color[c] * share, kPixelRelative)
            << pathName(plain) << ", metallic " << metal << " transmission " << kind.transmission;
    }
  }
}

// A metal mirror at 45 degrees under an orthographic camera shows an emissive wall: a pixel
// is the table's mirror reflectance base * metallic * (1 - roughness)^2 times the wall's
// colour (nothing lights its rough share), smooth and rough, tinted.
TEST(ShadingTerms, AMetalMirrorShowsItsColourTimesWhatItReflects) {
  for (const float roughness : {0.0f, 0.2f}) {
    Scene scene;
    Material metal, wall;
    metal.base_color = {0.8f, 0.6f, 0.4f};
    metal.metallic = 1.0f;
    metal.roughness = roughness;
    wall.base_color = glm::vec3(0.0f);
    wall.emissive = {0.9f, 0.5f, 1.0f};
    // The mirror's normal (0, 1, 1) / sqrt 2 turns rays going down (-Y) towards +Z.
    shapes::addRect(scene, {0, 0, 0}, {2, 0, 0}, {0, 2, -2}, shapes::addMaterial(scene, metal));
    shapes::addRect(scene, {0, 0, 5}, {0, 10, 0}, {10, 0, 0}, shapes::addMaterial(scene, wall));
    scene.has_lights = true;  // none
    const Camera camera = orthographic({0, 4, 0}, {0, 0, -1}, 0.5f);
    RenderSettings settings;
    settings.width = settings.height = 8;
    settings.ambient = 0.0f;
    const double kr = (1.0 - roughness) * (1.0 - roughness);
    for (const bool plain : {true, false}) {
      const Frame frame = render(scene, camera, settings, plain);
      for (int j = 0; j < 8; j += 3)
        for (int i = 0; i < 8; i += 3) {
          const glm::dvec3 got = pixelOf(frame, i, j);
          for (int c = 0; c < 3; ++c)
            EXPECT_NEAR(got[c], metal.base_color[c] * kr * wall.emissive[c], kPixelRelative)
                << pathName(plain) << ", roughness " << roughness << ", pixel " << i << "," << j;
        }
    }
  }
}

// A tinted glass slab tilted in front of an emissive wall, seen along -Z by an orthographic
// camera at several angles of incidence; two bounces after the primary hit: the light
// through both faces, base^2 (1 - F)^2 with F the angle form's (equal at both faces: they
// are parallel, and Fresnel's reflectance is the same either way through one), and beyond
// 45 degrees, where the front face's mirror image turns towards the wall, its F, untinted.
TEST(ShadingTerms, ATintedGlassSlabPassesBaseSquaredTimesOneMinusFresnelSquared) {
  for (const double degrees : {0.0, 30.0, 55.0, 70.0}) {
    const double theta = degrees * kPiD / 180.0;
    Scene scene;
    Material glass, wall;
    glass.base_color = {1.0f, 0.8f, 0.5f};
    glass.transmission = 1.0f;
    glass.roughness = 0.0f;
    glass.ior = 1.5f;
    wall.base_color = glm::vec3(0.0f);
    wall.emissive = {0.7f, 0.9f, 1.0f};
    const int g = shapes::addMaterial(scene, glass);
    // The slab's normal turned by theta about +Y; 0.3 thick, 8 across.
    shapes::addBox(scene, {0, 0, 0}, {4.0f, 4.0f, 0.15f}, float(theta), g);
    shapes::addRect(scene, {0, 0, -6}, {20, 0, 0}, {0, 20, 0}, shapes::addMaterial(scene, wall));
    scene.has_lights = true;  // none
    const Camera camera = orthographic({0, 0, 5}, {0, 1, 0}, 0.3f);
    RenderSettings settings;
    settings.width = settings.height = 8;
    settings.ambient = 0.0f;
    settings.max_depth = 2;
    const double f = fresnelOracle(theta, 1.0, 1.5);
    for (const bool plain : {true, false}) {
      const glm::dvec3 got = pixelOf(render(scene, camera, settings, plain), 4, 4);
      for (int c = 0; c < 3; ++c) {
        const double through = glass.base_color[c] * glass.base_color[c] * (1.0 - f) * (1.0 - f);
        const double reflected = std::cos(2.0 * theta) < 0.0 ? f : 0.0;
        const double want = (through + reflected) * wall.emissive[c];
        EXPECT_NEAR(got[c], want, kPixelRelative + kUnitTolerance)
            << pathName(plain) << ", " << degrees << " degrees, channel " << c;
      }
    }
  }
}

}  // namespace
}  // namespace gridrt
