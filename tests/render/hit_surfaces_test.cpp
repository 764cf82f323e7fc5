// The shading loop's surfaces and light directions, 16 hits at a time in lanes
// (host/render/hit_surfaces.h), against the one-hit formulation they replace: bit for bit, on
// random hits of random triangles (degenerate ones and hits without vertex normals
// included) and every kind of light.
#include "hit_surfaces.h"

#include <gtest/gtest.h>

#include <glm/glm.hpp>
#include <random>
#include <vector>

#include "test_support.h"
#include "whitted_shading.h"

namespace {

using namespace gridrt;

using test::sameBits;

// The one-hit surface: barycentrics of p in the triangle, interpolated normal, both
// normals turned towards the ray.
struct OneHit {
  glm::vec3 p, n, g;
  bool backface;
};

OneHit oneHit(const glm::vec3* v, const glm::vec3* normals, glm::vec3 geometric, glm::vec3 o,
              glm::vec3 d, float t) {
  OneHit h;
  h.p = o + t * d;
  glm::vec3 n = geometric;
  if (normals) {
    glm::vec3 e1 = v[1] - v[0], e2 = v[2] - v[0], w = h.p - v[0];
    float d11 = glm::dot(e1, e1), d12 = glm::dot(e1, e2), d22 = glm::dot(e2, e2);
    float w1 = glm::dot(w, e1), w2 = glm::dot(w, e2);
    float det = d11 * d22 - d12 * d12;
    glm::vec3 b(1.0f / 3.0f);
    if (det > 0.0f) {
      float b1 = (d22 * w1 - d12 * w2) / det, b2 = (d11 * w2 - d12 * w1) / det;
      b = glm::vec3(1.0f - b1 - b2, b1, b2);
    }
    glm::vec3 s = b.x * normals[0] + b.y * normals[1] + b.z * normals[2];
    float len = glm::length(s);
    if (len > 0.0f) n = s / len;
  }
  h.backface = glm::dot(geometric, d) > 0.0f;
  h.g = h.backface ? -geometric : geometric;
  h.n = glm::dot(n, h.g) < 0.0f ? -n : n;
  return h;
}

class HitSurfaces : public ::testing::TestWithParam<bool> {};

TEST_P(HitSurfaces, LanesEqualTheOneHitShadingBitForBit) {
  const bool smooth = GetParam();
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> coord(-3.0f, 3.0f), unit(-1.0f, 1.0f), dist(0.0f, 5.0f);
  Scene scene;
  const int triangles = 200;
  for (int i = 0; i < triangles; ++i) {
    glm::vec3 a(coord(rng), coord(rng), coord(rng)), b(coord(rng), coord(rng), coord(rng));
    glm::vec3 c = i % 10 == 0 ? a + 0.5f * (b - a) : glm::vec3(coord(rng), coord(rng), coord(rng));
    if (i % 17 == 0) b = a;  // degenerate: all barycentrics 1/3
    scene.positions.insert(scene.positions.end(), {a, b, c});
    for (int k = 0; k < 3; ++k) {
      glm::vec3 n(unit(rng), unit(rng), unit(rng));
      if (i % 13 == 0) n = glm::vec3(0.0f);  // vertex normals summing to zero
      if (smooth) scene.normals.push_back(n);
    }
    scene.material_of.push_back(0);
  }
  std::vector<glm::vec3> geometric(triangles);
  for (int i = 0; i < triangles; ++i) {
    glm::vec3 n = glm::cross(scene.positions[3 * i + 1] - scene.positions[3 * i],
                             scene.positions[3 * i + 2] - scene.positions[3 * i]);
    float len = glm::length(n);
    geometric[i] = len > 0.0f ? n / len : glm::vec3(0.0f, 0.0f, 1.0f);
  }
  const std::vector<ShadingTriangle> shading = makeShadingTriangles(scene, geometric);
  ASSERT_EQ(shading.size(), smooth ? size_t(triangles) : 0u);

  std::vector<Light> lights(5);
  lights[0].type = LightType::Point;
  lights[0].position = {0.5f, 4.0f, -1.0f};
  lights[0].intensity = 20.0f;
  lights[1] = lights[0];
  lights[1].range = 4.5f;  // the window's pow per lane
  lights[2].type = LightType::Spot;
  lights[2].position = {-1.0f, 3.0f, 2.0f};
  lights[2].direction = {0.3f, -1.0f, -0.4f};
  lights[2].inner_cone = 0.3f;
  lights[2].outer_cone = 0.7f;
  lights[2].intensity = 7.0f;
  lights[2].color = {1.0f, 0.5f, 0.25f};
  lights[3].type = LightType::Directional;
  lights[3].direction = {0.2f, -1.0f, 0.1f};
  lights[3].intensity = 3.0f;
  lights[4] = lights[0];
  lights[4].position = {0.0f, 0.0f, 0.0f};  // a hit point exactly on the light

  size_t lit = 0, unlit = 0;
  for (int block = 0; block < 400; ++block) {
    SurfaceLanes s;
    for (int k = 0; k < kSurfaceLanes; ++k) {
      s.tri[k] = int(rng() % triangles);
      glm::vec3 d = glm::normalize(glm::vec3(unit(rng), unit(rng), unit(rng)));
      s.ox[k] = coord(rng), s.oy[k] = coord(rng), s.oz[k] = coord(rng);
      s.dx[k] = d.x, s.dy[k] = d.y, s.dz[k] = d.z;
      s.t[k] = dist(rng);
      if (block == 0 && k == 0) s.ox[k] = s.oy[k] = s.oz[k] = s.t[k] = 0.0f;  // on light 4
    }
    computeSurfaces(smooth ? shading.data() : nullptr, geometric.data(), s);
    for (int k = 0; k < kSurfaceLanes; ++k) {
      const int t = s.tri[k];
      OneHit h =
          oneHit(&scene.positions[3 * t], smooth ? &scene.normals[3 * t] : nullptr, geometric[t],
                 {s.ox[k], s.oy[k], s.oz[k]}, {s.dx[k], s.dy[k], s.dz[k]}, s.t[k]);
      const float lanes[] = {s.px[k], s.py[k], s.pz[k], s.nx[k], s.ny[k],
                             s.nz[k], s.gx[k], s.gy[k], s.gz[k]};
      const float one[] = {h.p.x, h.p.y, h.p.z, h.n.x, h.n.y, h.n.z, h.g.x, h.g.y, h.g.z};
      for (int c = 0; c < 9; ++c)
        ASSERT_TRUE(sameBits(lanes[c], one[c]))
            << "block " << block << " lane " << k << " value " << c;
      ASSERT_EQ(bool(s.backface[k]), h.backface);
    }
    for (const Light& light : lights) {
      LightLanes l;
      computeLightLanes(light, s, l);
      for (int k = 0; k < kSurfaceLanes; ++k) {
        const glm::vec3 p(s.px[k], s.py[k], s.pz[k]), n(s.nx[k], s.ny[k], s.nz[k]),
            g(s.gx[k], s.gy[k], s.gz[k]);
        glm::vec3 to;
        float distance;
        const glm::vec3 e = lightIrradiance(light, p, to, distance);
        const float cos_theta = glm::dot(n, to);
        const bool one_lit =
            !(cos_theta <= 0.0f || glm::dot(g, to) <= 0.0f || glm::length(e) == 0.0f);
        ASSERT_EQ(bool(l.lit[k]), one_lit) << "block " << block << " lane " << k;
        if (!one_lit) {
          ++unlit;
          continue;
        }
        ++lit;
        const float lanes[] = {l.lx[k], l.ly[k], l.lz[k], l.distance[k],
                               l.ex[k], l.ey[k], l.ez[k], l.cos_theta[k]};
        const float one[] = {to.x, to.y, to.z, distance, e.x, e.y, e.z, cos_theta};
        for (int c = 0; c < 8; ++c)
          ASSERT_TRUE(sameBits(lanes[c], one[c]))
              << "block " << block << " lane " << k << " value " << c;
      }
    }
  }
  EXPECT_GT(lit, 1000u);
  EXPECT_GT(unlit, 1000u);
}

INSTANTIATE_TEST_SUITE_P(WithAndWithoutVertexNormals, HitSurfaces, ::testing::Bool());

}  // namespace
