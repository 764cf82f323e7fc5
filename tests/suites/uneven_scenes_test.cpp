// The uneven scenes (tools/uneven_scenes.h: a model on floors up to 1000 times its size,
// copies scattered far apart, a row, a huge triangle): batches too large for the device
// run in parts with the same hits bit for bit, and every path of the GridRT intersector
// equals brute force on every pixel.
#include "uneven_scenes.h"

#include <gtest/gtest.h>

#include <memory>
#include <random>

#include "adaptive_grid.h"
#include "brute_intersector.h"
#include "camera_rays.h"
#include "cl_runtime.h"
#include "default_scene.h"
#include "gltf_loader.h"
#include "gridrt_intersector.h"
#include "prepared_triangles.h"
#include "test_support.h"
#include "uniform_grid.h"

namespace gridrt {
namespace {

class UnevenScenes : public ::testing::Test {
 protected:
  void SetUp() override {
    if (listDevices().empty()) GTEST_SKIP() << "no OpenCL device: install pocl-opencl-icd";
    runtime_ = std::make_unique<ClRuntime>("");
  }

  static const Scene& model() {
    static const Scene bunny = loadGltfFile(test::modelScene("bunny_res4.glb"));
    return bunny;
  }

  static std::vector<GrRay> cameraRays(const Scene& scene, int w, int h) {
    std::vector<GrRay> rays;
    for (int j = 0; j < h; ++j)
      for (int i = 0; i < w; ++i) rays.push_back(cameraRay(scene.camera, w, h, i, j, 0.5f, 0.5f));
    return rays;
  }

  // Rays from random points of the scene's box in random directions.
  static std::vector<GrRay> randomRays(const Bounds& b, size_t count, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f), signed_unit(-1.0f, 1.0f);
    std::vector<GrRay> rays;
    while (rays.size() < count) {
      glm::vec3 o = b.lo + glm::vec3(unit(rng), unit(rng), unit(rng)) * b.extent();
      glm::vec3 d(signed_unit(rng), signed_unit(rng), signed_unit(rng));
      if (glm::length(d) < 0.1f) continue;
      d = glm::normalize(d);
      rays.push_back(GrRay{o.x, o.y, o.z, 0.0f, d.x, d.y, d.z, 1e30f});
    }
    return rays;
  }

  // Shadow rays from the points the camera rays hit towards `light`.
  static std::vector<GrRay> shadowRays(const std::vector<GrRay>& camera,
                                       const std::vector<GrHit>& hits, glm::vec3 light) {
    std::vector<GrRay> rays;
    for (size_t i = 0; i < camera.size(); ++i) {
      if (hits[i].prim < 0) continue;
      const GrRay& c = camera[i];
      glm::vec3 d(c.dx, c.dy, c.dz), p = glm::vec3(c.ox, c.oy, c.oz) + hits[i].t * d;
      glm::vec3 to = light - p;
      float distance = glm::length(to);
      if (!(distance > 0.0f)) continue;
      to /= distance;
      rays.push_back(GrRay{p.x, p.y, p.z, 1e-4f * distance, to.x, to.y, to.z, distance});
    }
    return rays;
  }

  // Every path of the GridRT intersector (camera bundles, traversal lists, light bundles;
  // with and without the interrupt) against brute force on `scene`'s camera rays, random
  // rays and shadow rays, closest hits bit for bit and any-hit answers hit for hit.
  // Returns the structure's depth below its top grid.
  int expectAllPathsMatchBrute(const Scene& scene, const GridSettings& settings, int w, int h,
                               const std::string& label) {
    const auto tris = prepareTriangles(scene);
    const Bounds b = sceneBounds(scene);
    GridSettings s = settings;
    s.ray_origins = primaryRayOrigins(scene.camera, w, h);
    const UniformGrid grid = buildGrid(tris, b, s);
    const std::string where = label + (grid.adaptive.empty() ? " uniform" : " adaptive") +
                              " depth " + std::to_string(grid.adaptive.depth) + ", " +
                              std::to_string(grid.peCount()) + " PEs";
    const PinholeView view = PinholeView::of(scene.camera, w, h, PixelWindow{});
    const std::vector<GrRay> camera = cameraRays(scene, w, h);
    const std::vector<GrRay> random = randomRays(b, 4000, 11);
    BruteIntersector brute(*runtime_, tris);
    std::vector<GrHit> want_camera, want_random, want_shadow, want_any, got;
    brute.intersect(camera, HitMode::Closest, want_camera, nullptr);
    brute.intersect(random, HitMode::Closest, want_random, nullptr);
    const glm::vec3 light = scene.lights.empty()
                                ? b.center() + glm::vec3(0.1f, 0.8f, 0.2f) * glm::length(b.extent())
                                : scene.lights[0].position;
    const std::vector<GrRay> shadow = shadowRays(camera, want_camera, light);
    brute.intersect(shadow, HitMode::Closest, want_shadow, nullptr);
    for (PeInterrupt interrupt :
         {PeInterrupt::Off, PeInterrupt::CameraRays, PeInterrupt::AllRays}) {
      const std::string at = where + " interrupt " + std::to_string(int(interrupt));
      GridRtIntersector gridrt(*runtime_, grid, interrupt);
      gridrt.intersectPrimary(view, camera, got, nullptr);
      EXPECT_EQ(test::hitMismatches(want_camera, got, at + " camera bundles"), 0u);
      gridrt.intersect(camera, HitMode::Closest, got, nullptr);
      EXPECT_EQ(test::hitMismatches(want_camera, got, at + " camera rays as lists"), 0u);
      gridrt.intersect(random, HitMode::Closest, got, nullptr);
      EXPECT_EQ(test::hitMismatches(want_random, got, at + " random rays"), 0u);
      gridrt.intersectTowardsPoint(light, shadow, HitMode::Closest, got);
      EXPECT_EQ(test::hitMismatches(want_shadow, got, at + " shadow rays"), 0u);
      gridrt.forceLightBundles();
      gridrt.intersectTowardsPoint(light, shadow, HitMode::Closest, got);
      EXPECT_EQ(test::hitMismatches(want_shadow, got, at + " light bundles"), 0u);
      gridrt.intersectTowardsPoint(light, shadow, HitMode::AnyHit, got);
      size_t differ = 0;
      for (size_t i = 0; i < shadow.size(); ++i)
        differ += (got[i].prim >= 0) != (want_shadow[i].prim >= 0);
      EXPECT_EQ(differ, 0u) << at << " light bundles any-hit";
    }
    return grid.adaptive.depth;
  }

  std::unique_ptr<ClRuntime> runtime_;
};

// A batch buffer limit far below what the batches need: the camera bundles, the light
// bundles and the traversal lists each run in many parts, with the hits of one batch.
TEST_F(UnevenScenes, BatchesSplitToFitASmallDeviceLimitGiveTheSameHitsBitForBit) {
  const Scene scene = floorScene(model(), 10.0f);
  const auto tris = prepareTriangles(scene);
  const Bounds b = sceneBounds(scene);
  GridSettings settings;
  settings.ray_origins = primaryRayOrigins(scene.camera, 160, 120);
  const UniformGrid grid = buildUniformGrid(tris, b, settings);
  const PinholeView view = PinholeView::of(scene.camera, 160, 120, PixelWindow{});
  const std::vector<GrRay> camera = cameraRays(scene, 160, 120);
  BruteIntersector brute(*runtime_, tris);
  std::vector<GrHit> want_camera;
  brute.intersect(camera, HitMode::Closest, want_camera, nullptr);
  const std::vector<GrRay> shadow = shadowRays(camera, want_camera, scene.lights.at(0).position);
  const std::vector<GrRay> random = randomRays(b, 20000, 7);

  for (PeInterrupt interrupt : {PeInterrupt::CameraRays, PeInterrupt::AllRays}) {
    // The parts cross to the device both ways (BatchTransfer), one with each interrupt.
    KernelOptions parts_options;
    parts_options.transfer =
        interrupt == PeInterrupt::CameraRays ? BatchTransfer::Map : BatchTransfer::Copy;
    GridRtIntersector whole(*runtime_, grid, interrupt),
        parts(*runtime_, grid, interrupt, parts_options);
    parts.setBatchBufferLimit(64 << 10);  // 64 KiB: a few thousand lanes a part
    whole.forceLightBundles();
    parts.forceLightBundles();
    std::vector<GrHit> a, c;
    whole.intersectPrimary(view, camera, a, nullptr);
    parts.intersectPrimary(view, camera, c, nullptr);
    EXPECT_EQ(test::hitMismatches(a, c, "camera bundles split"), 0u);
    EXPECT_EQ(test::hitMismatches(want_camera, c, "camera bundles split against brute"), 0u);
    const uint64_t after_camera = parts.counters().split_batches;
    EXPECT_GT(after_camera, 0u) << "the camera batch should have run in parts";

    // Closest hits equal bit for bit; any-hit queries may report any occluder, so only
    // whether there is one must agree.
    auto expectSame = [](HitMode mode, const std::vector<GrHit>& x, const std::vector<GrHit>& y,
                         const std::string& label) {
      if (mode == HitMode::Closest) {
        EXPECT_EQ(test::hitMismatches(x, y, label), 0u);
        return;
      }
      ASSERT_EQ(x.size(), y.size());
      size_t differ = 0;
      for (size_t i = 0; i < x.size(); ++i) differ += (x[i].prim >= 0) != (y[i].prim >= 0);
      EXPECT_EQ(differ, 0u) << label;
    };
    for (HitMode mode : {HitMode::Closest, HitMode::AnyHit}) {
      whole.intersectTowardsPoint(scene.lights[0].position, shadow, mode, a);
      parts.intersectTowardsPoint(scene.lights[0].position, shadow, mode, c);
      expectSame(mode, a, c, "light bundles split");
      whole.intersect(random, mode, a, nullptr);
      parts.intersect(random, mode, c, nullptr);
      expectSame(mode, a, c, "traversal lists split");
    }
    std::vector<GrHit> want_random;
    brute.intersect(random, HitMode::Closest, want_random, nullptr);
    parts.intersect(random, HitMode::Closest, c, nullptr);
    EXPECT_EQ(test::hitMismatches(want_random, c, "traversal lists split against brute"), 0u);
    EXPECT_GT(parts.counters().split_batches, after_camera) << "lists should have run in parts";
    EXPECT_EQ(whole.counters().split_batches, 0u);
  }
}

// The family made of bunny_res4 (950 triangles), each scene with the adaptive structure at
// three leaf sizes (256: the default, which splits only the cells around the model on the
// large floors; 32 and 8 reach two and three levels below the top) and two densities, and
// the uniform auto grid.
class UnevenFamily : public UnevenScenes, public ::testing::WithParamInterface<std::string> {};

TEST_P(UnevenFamily, EveryPathMatchesBruteOnEveryPixel) {
  Scene scene;
  for (auto& [name, s] : unevenScenes(model(), 8))
    if (name == GetParam()) scene = std::move(s);
  ASSERT_GT(scene.triangleCount(), 0u);
  std::vector<GridSettings> settings;
  for (int leaf : {256, 32, 8})
    for (float density : {kDefaultGridDensity, 0.5f}) {
      GridSettings s;
      s.structure = GridStructure::Adaptive;
      s.max_leaf_triangles = leaf;
      s.density = density;
      settings.push_back(s);
    }
  settings.push_back(GridSettings{});  // uniform
  int depth = 0;
  for (const GridSettings& s : settings)
    depth = std::max(depth, expectAllPathsMatchBrute(scene, s, 96, 72,
                                                     GetParam() + " leaf " +
                                                         std::to_string(s.max_leaf_triangles) +
                                                         " density " + std::to_string(s.density)));
  EXPECT_GE(depth, 2) << "the small leaves should reach two levels below the top grid";
}

// The scenes that are even already (the default scene, whose glass sphere's voxels the
// adaptive structure refines, bunny_res4 and the teapot), with the adaptive structure at
// the default leaf limit and at 16, against brute force the same way.
TEST_F(UnevenScenes, TheAdaptiveStructureMatchesBruteOnTheEvenScenes) {
  std::vector<std::pair<std::string, Scene>> scenes;
  scenes.emplace_back("default scene", makeDefaultScene());
  scenes.emplace_back("bunny_res4", model());
  scenes.emplace_back("teapot", loadGltfFile(test::modelScene("teapot.glb")));
  for (auto& [name, scene] : scenes) {
    if (!scene.has_camera) scene.camera = defaultCamera(sceneBounds(scene));
    for (int leaf : {256, 16}) {
      GridSettings s;
      s.structure = GridStructure::Adaptive;
      s.max_leaf_triangles = leaf;
      const int depth =
          expectAllPathsMatchBrute(scene, s, 96, 72, name + " leaf " + std::to_string(leaf));
      if (leaf == 16) {
        EXPECT_GE(depth, 1) << name;
      }
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Family, UnevenFamily,
                         ::testing::Values("floor_1x", "floor_10x", "floor_100x", "floor_1000x",
                                           "scattered", "row", "huge_triangle"));

}  // namespace
}  // namespace gridrt
