// The plain path of the Whitted loop (host/render/plain_shading.h): every lane's values bit
// for bit those of the one-hit functions (rayOffsetDistance, offsetRayOrigin, the Phong
// term in GLM), lanes that are not plain left alone, and whole frames with the plain path
// equal to frames where every hit takes the one-hit loop.
#include "plain_shading.h"

#include <gtest/gtest.h>

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

// A material that blends, or has a mirror, is not plain: its hits spawn rays.
TEST_F(PlainShadingFrames, BlendingAndMirrorsStayOnTheOneHitLoop) {
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
