// The plain path of the Whitted loop (host/render/plain_shading.h): every lane's values bit
// for bit those of the one-hit functions (rayOffsetDistance, offsetRayOrigin, the Phong
// term in GLM), lanes that are not plain left alone, and whole frames with the plain path
// equal to frames where every hit takes the one-hit loop.
#include "plain_shading.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <string>

#include "default_scene_fixture.h"
#include "gridrt_intersector.h"
#include "renderer.h"
#include "test_support.h"
#include "uniform_grid.h"

namespace gridrt {
namespace {

constexpr int L = kSurfaceLanes;

using test::sameBits;

// Material 0 plain, 1 not (a mirror, say), 2 plain and emissive.
std::vector<PlainMaterial> materials() {
  std::vector<PlainMaterial> m(3);
  m[0] = {1, glm::vec3(0.6f, 0.3f, 0.1f), glm::vec3(0.04f), glm::vec3(0.0f)};
  m[1] = {0, glm::vec3(0.5f), glm::vec3(0.5f), glm::vec3(0.0f)};
  m[2] = {1, glm::vec3(0.2f, 0.7f, 0.9f), glm::vec3(0.3f, 0.2f, 0.1f),
          glm::vec3(1.5f, 0.5f, 0.25f)};
  return m;
}

// Random hit points, origins and unit normals over many scales, with a coordinate 0 or a
// normal component 0 now and then (nextFloat's own cases).
void fill(SurfaceLanes& s, PlainLanes& p, std::mt19937& rng) {
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f), exponent(-6.0f, 6.0f);
  for (int k = 0; k < L; ++k) {
    const float scale = std::pow(10.0f, exponent(rng));
    s.px[k] = k % 5 == 0 ? 0.0f : scale * unit(rng);
    s.py[k] = scale * unit(rng);
    s.pz[k] = scale * unit(rng);
    s.ox[k] = scale * 3.0f * unit(rng), s.oy[k] = scale * unit(rng), s.oz[k] = unit(rng);
    glm::vec3 n(unit(rng), k % 3 == 0 ? 0.0f : unit(rng), unit(rng));
    n = glm::normalize(n);
    s.gx[k] = n.x, s.gy[k] = n.y, s.gz[k] = n.z;
    p.wr[k] = 0.5f + 0.5f * unit(rng), p.wg[k] = 0.5f + 0.5f * unit(rng), p.wb[k] = 1.0f;
    p.material[k] = k % 3;
  }
}

TEST(PlainShading, LanesEqualTheOneHitFunctions) {
  std::mt19937 rng(11);
  const std::vector<PlainMaterial> m = materials();
  for (const bool robust : {true, false}) {
    RayOffset offset;
    offset.robust = robust;
    offset.epsilon = 3e-4f;
    for (int round = 0; round < 200; ++round) {
      SurfaceLanes s{};
      PlainLanes p{};
      fill(s, p, rng);
      const float ambient = 0.05f;
      computePlainLanes(s, m.data(), ambient, offset, p);
      for (int k = 0; k < L; ++k) {
        const PlainMaterial& mat = m[p.material[k]];
        EXPECT_EQ(p.plain[k], mat.plain) << k;
        const glm::vec3 point(s.px[k], s.py[k], s.pz[k]), normal(s.gx[k], s.gy[k], s.gz[k]);
        const float distance =
            rayOffsetDistance(point, glm::vec3(s.ox[k], s.oy[k], s.oz[k]), offset);
        const glm::vec3 above = offsetRayOrigin(point, normal, distance, offset);
        const glm::vec3 weight(p.wr[k], p.wg[k], p.wb[k]);
        const glm::vec3 own = weight * (mat.emissive + ambient * mat.diffuse);
        ASSERT_TRUE(sameBits(p.offset[k], distance)) << k;
        ASSERT_TRUE(sameBits(p.ax[k], above.x) && sameBits(p.ay[k], above.y) &&
                    sameBits(p.az[k], above.z))
            << "lane " << k << " robust " << robust;
        ASSERT_TRUE(sameBits(p.lr[k], own.x) && sameBits(p.lg[k], own.y) &&
                    sameBits(p.lb[k], own.z))
            << k;
      }
    }
  }
}

TEST(PlainShading, LanesThatAreNotFiniteKeepTheOneHitLoop) {
  std::mt19937 rng(3);
  const std::vector<PlainMaterial> m = materials();
  SurfaceLanes s{};
  PlainLanes p{};
  fill(s, p, rng);
  for (int k = 0; k < L; ++k) p.material[k] = 0;
  const float inf = std::numeric_limits<float>::infinity();
  s.px[1] = inf;
  s.oy[2] = std::nanf("");
  s.gz[3] = std::nanf("");
  s.px[4] = std::numeric_limits<float>::max();  // p + distance * n overflows...
  s.gx[4] = 1.0f, s.gy[4] = 0.0f, s.gz[4] = 0.0f;
  s.ox[4] = 0.0f;
  computePlainLanes(s, m.data(), 0.05f, RayOffset{}, p);
  for (int k = 0; k < L; ++k) EXPECT_EQ(p.plain[k], k >= 1 && k <= 4 ? 0 : 1) << k;
}

TEST(PlainShading, LightContributionsEqualThePhongTerm) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  const std::vector<PlainMaterial> m = materials();
  for (int round = 0; round < 200; ++round) {
    SurfaceLanes s{};
    PlainLanes p{};
    fill(s, p, rng);
    LightLanes light{};
    for (int k = 0; k < L; ++k) {
      light.ex[k] = 10.0f * unit(rng), light.ey[k] = unit(rng), light.ez[k] = unit(rng);
      light.cos_theta[k] = unit(rng);
      light.highlight[k] = unit(rng);
      light.lit[k] = k % 4 != 1;
    }
    light.ex[6] = light.ey[6] = light.ez[6] = 0.0f;  // lit, but nothing arrives
    PlainLightLanes out{};
    computePlainLight(p, m.data(), light, out);
    for (int k = 0; k < L; ++k) {
      const PlainMaterial& mat = m[p.material[k]];
      const glm::vec3 e(light.ex[k], light.ey[k], light.ez[k]);
      const glm::vec3 direct =
          mat.diffuse / kPi * e * light.cos_theta[k] + mat.specular * e * light.highlight[k];
      const glm::vec3 c = glm::vec3(p.wr[k], p.wg[k], p.wb[k]) * direct;
      ASSERT_TRUE(sameBits(out.cr[k], c.x) && sameBits(out.cg[k], c.y) && sameBits(out.cb[k], c.z))
          << k;
      EXPECT_EQ(out.emit[k], light.lit[k] && glm::dot(c, c) != 0.0f) << k;
    }
    EXPECT_EQ(out.emit[6], 0);
    EXPECT_EQ(out.emit[1], 0);
  }
}

// The spawned rays of the one-hit loop, from the one-hit functions (fresnelDielectric,
// refractDirection, offsetRayOrigin) and its own expressions.
struct OneHitSpawn {
  bool refract = false, reflect = false;
  glm::vec3 refract_origin, refract_dir, refract_weight, reflect_dir, reflect_weight;
};
OneHitSpawn oneHitSpawn(const SurfaceLanes& s, const PlainLanes& p, const PlainMaterial& m,
                        const RayOffset& offset, float min_path_weight, int k) {
  auto worth = [&](const glm::vec3& w) { return std::max({w.x, w.y, w.z}) >= min_path_weight; };
  const glm::vec3 d(s.dx[k], s.dy[k], s.dz[k]), n(s.nx[k], s.ny[k], s.nz[k]);
  const glm::vec3 ng(s.gx[k], s.gy[k], s.gz[k]), point(s.px[k], s.py[k], s.pz[k]);
  const glm::vec3 weight(p.wr[k], p.wg[k], p.wb[k]);
  OneHitSpawn o;
  glm::vec3 reflect_weight = m.mirror;
  if (m.transmission > 0.0f) {
    const float eta = s.backface[k] ? m.ior : 1.0f / m.ior;
    float f = fresnelDielectric(-glm::dot(d, n), eta);
    o.refract_weight = weight * m.transmission * (1.0f - f) * m.base_color;
    if (f < 1.0f && refractDirection(d, n, eta, o.refract_dir) &&
        glm::dot(o.refract_dir, ng) < 0.0f) {
      o.refract = worth(o.refract_weight);
      o.refract_origin = offsetRayOrigin(point, -ng, p.offset[k], offset);
    } else {
      f = 1.0f;
    }
    reflect_weight += glm::vec3(m.transmission * f);
  }
  o.reflect_weight = weight * reflect_weight;
  o.reflect = glm::dot(reflect_weight, reflect_weight) > 0.0f && worth(o.reflect_weight);
  o.reflect_dir = d - 2.0f * glm::dot(d, n) * n;
  if (glm::dot(o.reflect_dir, ng) <= 0.0f) o.reflect_dir = d - 2.0f * glm::dot(d, ng) * ng;
  return o;
}

bool sameVector(const glm::vec3& a, float x, float y, float z) {
  return sameBits(a.x, x) && sameBits(a.y, y) && sameBits(a.z, z);
}

// Glass of two densities, a mirror, and glass with a mirror's share; rays from both sides,
// shading normals that face away from the ray now and then (interpolated normals do, at a
// silhouette), geometric normals off the shading ones, weights exactly at the floor.
TEST(PlainShading, SpawnLanesEqualTheOneHitFunctions) {
  std::vector<PlainMaterial> m(4);
  for (PlainMaterial& x : m) x.plain = 1, x.spawning = 1, x.base_color = glm::vec3(1.0f);
  m[0].transmission = 1.0f;
  m[1].transmission = 1.0f, m[1].ior = 2.4f, m[1].base_color = glm::vec3(0.9f, 0.6f, 0.3f);
  m[2].mirror = glm::vec3(0.95f, 0.9f, 0.85f);
  m[3].transmission = 0.5f, m[3].mirror = glm::vec3(0.25f), m[3].ior = 1.33f;
  const float floor = 0.25f;
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  size_t refracted = 0, reflected = 0, inside = 0, away = 0, at_floor = 0;
  for (int round = 0; round < 200; ++round) {
    SurfaceLanes s;
    PlainLanes p;
    fill(s, p, rng);
    for (int k = 0; k < L; ++k) {
      const glm::vec3 d = glm::normalize(glm::vec3(unit(rng), unit(rng), unit(rng)));
      glm::vec3 n = glm::normalize(glm::vec3(unit(rng), unit(rng), unit(rng)));
      if (glm::dot(n, d) > 0.0f && k % 7 != 0) n = -n;  // facing the ray, but now and then
      away += glm::dot(n, d) > 0.0f;
      const glm::vec3 ng = glm::normalize(n + 0.2f * glm::vec3(unit(rng), unit(rng), unit(rng)));
      s.dx[k] = d.x, s.dy[k] = d.y, s.dz[k] = d.z;
      s.nx[k] = n.x, s.ny[k] = n.y, s.nz[k] = n.z;
      s.gx[k] = ng.x, s.gy[k] = ng.y, s.gz[k] = ng.z;
      s.backface[k] = k % 2;
      inside += k % 2;
      p.material[k] = (round + k) % 4;
      if (k % 5 == 0) p.wr[k] = floor / 0.95f, p.wg[k] = p.wb[k] = 0.0f;  // at the floor
    }
    for (const bool robust : {true, false}) {
      RayOffset offset;
      offset.robust = robust;
      computePlainLanes(s, m.data(), 0.05f, offset, p);
      SpawnLanes out;
      computeSpawnLanes(s, m.data(), offset, floor, p, out);
      for (int k = 0; k < L; ++k) {
        ASSERT_TRUE(p.plain[k]);
        const OneHitSpawn want = oneHitSpawn(s, p, m[p.material[k]], offset, floor, k);
        EXPECT_EQ(bool(out.refract[k]), want.refract) << "lane " << k;
        EXPECT_EQ(bool(out.reflect[k]), want.reflect) << "lane " << k;
        if (want.refract) {
          ++refracted;
          EXPECT_TRUE(sameVector(want.refract_origin, out.rox[k], out.roy[k], out.roz[k]));
          EXPECT_TRUE(sameVector(want.refract_dir, out.rdx[k], out.rdy[k], out.rdz[k]));
          EXPECT_TRUE(sameVector(want.refract_weight, out.rwr[k], out.rwg[k], out.rwb[k]));
        }
        if (want.reflect) {
          ++reflected;
          at_floor += std::max({want.reflect_weight.x, want.reflect_weight.y,
                                want.reflect_weight.z}) == floor;
          EXPECT_TRUE(sameVector(want.reflect_dir, out.fdx[k], out.fdy[k], out.fdz[k]));
          EXPECT_TRUE(sameVector(want.reflect_weight, out.fwr[k], out.fwg[k], out.fwb[k]));
        }
      }
    }
  }
  EXPECT_GT(refracted, 1000u);
  EXPECT_GT(reflected, 1000u);
  EXPECT_GT(inside, 1000u);
  EXPECT_GT(away, 100u);
  EXPECT_GT(at_floor, 10u);
}

class PlainShadingFrames : public test::DefaultSceneTest {
 protected:
  Frame render(const Scene& scene, RenderSettings settings, bool plain_lanes) {
    const UniformGrid grid =
        buildUniformGrid(prepareTriangles(scene), sceneBounds(scene), GridSettings{});
    GridRtIntersector gridrt(*runtime_, grid, PeInterrupt::Off);
    settings.plain_lanes = plain_lanes;
    Renderer renderer(scene, scene.camera, gridrt, settings);
    Frame frame;
    renderer.render(frame);
    return frame;
  }
  void expectSameFrame(const Scene& scene, const RenderSettings& settings,
                       const std::string& what) {
    const Frame want = render(scene, settings, false), got = render(scene, settings, true);
    ASSERT_EQ(want.film.rgb.size(), got.film.rgb.size()) << what;
    size_t differing = 0;
    for (size_t k = 0; k < want.film.rgb.size(); ++k)
      differing += !sameBits(want.film.rgb[k], got.film.rgb[k]);
    EXPECT_EQ(differing, 0u) << what;
    EXPECT_EQ(want.rays.shadow, got.rays.shadow) << what;
    EXPECT_EQ(want.rays.total(), got.rays.total()) << what;
  }
};

// The default scene mixes plain walls and spheres with a mirror and glass, so blocks hold
// both kinds of hit; each shadow ray must come out in the same place of the same order.
TEST_F(PlainShadingFrames, EqualTheOneHitLoop) {
  RenderSettings s;
  s.width = 120;
  s.height = 90;
  expectSameFrame(scene_, s, "default");
  RenderSettings jittered = s;
  jittered.spp = 2;
  expectSameFrame(scene_, jittered, "spp 2");
  RenderSettings epsilon = s;
  epsilon.ray_offset.robust = false;
  epsilon.ray_offset.epsilon = 1e-3f;
  expectSameFrame(scene_, epsilon, "epsilon offset");
  RenderSettings brighter = s;
  brighter.ambient = 0.3f;
  expectSameFrame(scene_, brighter, "ambient 0.3");
}

// The mirror's and the glass's hits spawn their reflection and refraction rays in lanes:
// with rays too faint to trace, at every depth limit, through denser glass (more total
// internal reflection), and beside a glass that absorbs (which keeps the one-hit loop).
TEST_F(PlainShadingFrames, SpawnedRaysEqualTheOneHitLoop) {
  RenderSettings s;
  s.width = 120;
  s.height = 90;
  RenderSettings faint = s;
  faint.min_path_weight = 0.05f;
  expectSameFrame(scene_, faint, "min path weight 0.05");
  for (int depth : {0, 1, 3}) {
    RenderSettings shallow = s;
    shallow.max_depth = depth;
    expectSameFrame(scene_, shallow, "max depth " + std::to_string(depth));
  }
  size_t glass = 0;
  for (size_t i = 0; i < scene_.materials.size(); ++i)
    if (scene_.materials[i].transmission > 0.0f) glass = i;
  ASSERT_GT(scene_.materials[glass].transmission, 0.0f);
  Scene dense = scene_;
  dense.materials[glass].ior = 2.4f;
  dense.materials[glass].base_color = glm::vec3(0.9f, 0.6f, 0.3f);
  expectSameFrame(dense, s, "ior 2.4, tinted");
  Scene absorbing = scene_;
  absorbing.materials[glass].attenuation_distance = 0.5f;
  absorbing.materials[glass].attenuation_color = glm::vec3(0.5f, 0.8f, 0.9f);
  expectSameFrame(absorbing, s, "absorbing glass");
}

// A material that blends stays on the one-hit loop; one made a mirror takes the lanes.
TEST_F(PlainShadingFrames, BlendedAndMirroredWallsEqualTheOneHitLoop) {
  RenderSettings s;
  s.width = 96;
  s.height = 72;
  for (size_t i = 0; i < scene_.materials.size(); ++i) {
    const Material& m = scene_.materials[i];
    if (m.transmission > 0.0f || m.metallic > 0.0f) continue;
    Scene blend = scene_;
    blend.materials[i].alpha_mode = AlphaMode::Blend;
    blend.materials[i].base_alpha = 0.5f;
    expectSameFrame(blend, s, "blend " + std::to_string(i));
    Scene mirror = scene_;
    mirror.materials[i].metallic = 1.0f;
    mirror.materials[i].roughness = 0.0f;
    expectSameFrame(mirror, s, "mirror " + std::to_string(i));
  }
}

}  // namespace
}  // namespace gridrt
