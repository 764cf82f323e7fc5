// Conformance: the grid intersectors (gridrt, gridrt with the emulated interrupt, dda)
// return exactly the hits of the brute-force kernel — same primitive id, same t bit for
// bit — on every pixel of every scene at several grid resolutions, on random rays, and
// on the cases where the GridRT method fails if done carelessly.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <memory>
#include <optional>
#include <random>

#include "adaptive_grid.h"
#include "brute_intersector.h"
#include "camera_rays.h"
#include "cl_runtime.h"
#include "dda_intersector.h"
#include "default_scene.h"
#include "gltf_loader.h"
#include "gridrt_intersector.h"
#include "kernel_choices.h"
#include "prepared_triangles.h"
#include "segment_culling.h"
#include "test_support.h"
#include "test_triangles.h"
#include "uniform_grid.h"

namespace gridrt {
namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();

class ConformanceFixture : public ::testing::Test {
 protected:
  void SetUp() override {
    if (listDevices().empty()) GTEST_SKIP() << "no OpenCL device: install pocl-opencl-icd";
    runtime_ = std::make_unique<ClRuntime>("");
  }

  // Runs every grid intersector at each setting against brute force on `rays`.
  // With `view`, the rays are a pinhole camera's and the footprint-binned primary path
  // of GridRT (intersectPrimary) is checked too.
  void expectAllAgree(const std::vector<GrTriangle>& tris, const Bounds& bounds,
                      const std::vector<GrRay>& rays, const std::vector<GridSettings>& grids,
                      const std::string& label, const PinholeView* view = nullptr) {
    BruteIntersector brute(*runtime_, tris);
    std::vector<GrHit> want, got;
    brute.intersect(rays, HitMode::Closest, want, nullptr);
    std::vector<GrHit> want_any;
    brute.intersect(rays, HitMode::AnyHit, want_any, nullptr);
    for (const auto& settings : grids) {
      UniformGrid grid = buildUniformGrid(tris, bounds, settings);
      std::string where = label + " grid " + std::to_string(grid.info.nx) + "x" +
                          std::to_string(grid.info.ny) + "x" + std::to_string(grid.info.nz);
      // The lane kernels cull nothing: on a grid of PEs this full they are brute force
      // (seconds on a CPU device), and the packet kernels alone check it.
      if (kernels_ && kernels_->pe_layout == PeLayout::Lanes && !otherLayoutAffordable(grid))
        continue;
      const KernelOptions options = kernels_ ? *kernels_ : KernelOptions{};
      GridRtIntersector gridrt(*runtime_, grid, PeInterrupt::Off, options);
      GridRtIntersector interrupt(*runtime_, grid, PeInterrupt::AllRays, options);
      GridRtIntersector camera_interrupt(*runtime_, grid, PeInterrupt::CameraRays, options);
      DdaIntersector dda(*runtime_, grid);
      gridrt.intersect(rays, HitMode::Closest, got, nullptr);
      EXPECT_EQ(test::hitMismatches(want, got, where + " gridrt"), 0u);
      interrupt.intersect(rays, HitMode::Closest, got, nullptr);
      EXPECT_EQ(test::hitMismatches(want, got, where + " gridrt-interrupt"), 0u);
      if (view) {
        gridrt.intersectPrimary(*view, rays, got, nullptr);
        EXPECT_EQ(test::hitMismatches(want, got, where + " gridrt camera path"), 0u);
        interrupt.intersectPrimary(*view, rays, got, nullptr);
        EXPECT_EQ(test::hitMismatches(want, got, where + " gridrt-interrupt camera path"), 0u);
        camera_interrupt.intersectPrimary(*view, rays, got, nullptr);
        EXPECT_EQ(test::hitMismatches(want, got, where + " camera-interrupt camera path"), 0u);
      }
      dda.intersect(rays, HitMode::Closest, got, nullptr);
      EXPECT_EQ(test::hitMismatches(want, got, where + " dda"), 0u);
      // Unless the test names its kernels (Conformance): the PE kernels of the layout
      // this device does not pick by itself (PeLayout), their batches copied across
      // (BatchTransfer), with the interrupt: the same hits on every path.
      GridRtIntersector other(*runtime_, grid, PeInterrupt::AllRays, otherChoices());
      std::vector<Intersector*> any_hit_checked = {&gridrt, &dda};
      if (!kernels_ && otherLayoutAffordable(grid)) {
        other.intersect(rays, HitMode::Closest, got, nullptr);
        EXPECT_EQ(test::hitMismatches(want, got, where + " other layout and transfer"), 0u);
        if (view) {
          other.intersectPrimary(*view, rays, got, nullptr);
          EXPECT_EQ(
              test::hitMismatches(want, got, where + " other layout and transfer camera path"), 0u);
        }
        any_hit_checked.push_back(&other);
      }
      // Any-hit (shadow) mode: hit or miss must agree with the closest-hit answer.
      for (Intersector* x : any_hit_checked) {
        x->intersect(rays, HitMode::AnyHit, got, nullptr);
        size_t differ = 0;
        for (size_t i = 0; i < rays.size(); ++i)
          differ += (got[i].prim >= 0) != (want[i].prim >= 0);
        EXPECT_EQ(differ, 0u) << where << " " << x->name() << " any-hit";
      }
    }
  }

  // The PE kernels' layout this device's default (PeLayout::Auto) does not pick, and the
  // batch transfer that is not the default (BatchTransfer::Copy).
  KernelOptions otherChoices() const {
    KernelOptions options;
    options.pe_layout = peLayoutFor(PeLayout::Auto, runtime_->info()) == PeLayout::Packets
                            ? PeLayout::Lanes
                            : PeLayout::Packets;
    options.transfer = BatchTransfer::Copy;
    return options;
  }
  // The lane kernels cull nothing: on a grid of a few large PEs (the 69k-triangle bunny in
  // one voxel) they are brute force, minutes on a CPU device. They are checked where a PE
  // holds at most this many triangles on average.
  static constexpr size_t kOtherLayoutMaxMeanPeTriangles = 512;
  static bool otherLayoutAffordable(const UniformGrid& grid) {
    return grid.pe_triangles.size() <=
           kOtherLayoutMaxMeanPeTriangles * std::max<size_t>(grid.peCount(), 1);
  }

  static Camera cameraOf(const Scene& scene) {
    return scene.has_camera ? scene.camera : defaultCamera(sceneBounds(scene));
  }

  static std::vector<GrRay> cameraRays(const Scene& scene, int w, int h) {
    Camera camera = cameraOf(scene);
    std::vector<GrRay> rays;
    for (int j = 0; j < h; ++j)
      for (int i = 0; i < w; ++i) rays.push_back(cameraRay(camera, w, h, i, j, 0.5f, 0.5f));
    return rays;
  }

  static std::vector<GridSettings> standardGrids(const Bounds& b, size_t triangles) {
    GridSettings one, three, fine, automatic;
    one.automatic = three.automatic = fine.automatic = false;
    one.dims = {1, 1, 1};
    three.dims = {3, 3, 3};
    // "Very fine": four times the auto resolution per axis (64x the voxels).
    fine.dims =
        glm::min(autoGridResolution(b, triangles, kDefaultGridDensity) * 4, glm::ivec3(160));
    return {one, three, automatic, fine};
  }

  // Shadow rays from the surface points `camera` rays hit towards `light`, the way the
  // renderer makes them (direction and distance from the hit point), but with origins
  // moved back along the camera ray by `offset`: their ends miss the light by `offset`.
  static std::vector<GrRay> shadowRays(const std::vector<GrRay>& camera,
                                       const std::vector<GrHit>& hits, glm::vec3 light,
                                       float offset) {
    std::vector<GrRay> rays;
    for (size_t i = 0; i < camera.size(); ++i) {
      if (hits[i].prim < 0) continue;
      const GrRay& c = camera[i];
      glm::vec3 d(c.dx, c.dy, c.dz), p = glm::vec3(c.ox, c.oy, c.oz) + hits[i].t * d;
      glm::vec3 o = p - offset * d, to = light - p;
      float distance = glm::length(to);
      if (!(distance > 0.0f)) continue;
      to /= distance;
      rays.push_back(GrRay{o.x, o.y, o.z, 0.0f, to.x, to.y, to.z, distance});
    }
    return rays;
  }

  // GridRT's light bundles (intersectTowardsPoint) against brute force, closest and any
  // hit, for a light above the scene and one inside it (voxels around the light receive
  // every ray), with origins near the surface and pulled well away from it.
  void expectLightPathAgrees(const std::vector<GrTriangle>& tris, const Bounds& b,
                             const std::vector<GrRay>& camera,
                             const std::vector<GridSettings>& grids, const std::string& label) {
    BruteIntersector brute(*runtime_, tris);
    std::vector<GrHit> camera_hits, want, got;
    brute.intersect(camera, HitMode::Closest, camera_hits, nullptr);
    const float size = glm::length(b.extent());
    // (light, offset): above with near and far origins; inside with near ones (far ones
    // inside a fine grid ask for gigabytes of lanes: the renderer falls back to lists).
    const std::pair<glm::vec3, float> cases[] = {
        {b.center() + glm::vec3(0.1f, 0.8f, 0.2f) * size, 1e-4f * size},
        {b.center() + glm::vec3(0.1f, 0.8f, 0.2f) * size, 2e-3f * size},
        {b.center(), 1e-4f * size}};
    for (const auto& [light, offset] : cases) {
      std::vector<GrRay> rays = shadowRays(camera, camera_hits, light, offset);
      brute.intersect(rays, HitMode::Closest, want, nullptr);
      for (const GridSettings& settings : grids) {
        UniformGrid grid = buildUniformGrid(tris, b, settings);
        std::string where = label + " light (" + std::to_string(light.x) + ", " +
                            std::to_string(light.y) + ", " + std::to_string(light.z) + ") offset " +
                            std::to_string(offset) + " grid " + std::to_string(grid.info.nx) + "x" +
                            std::to_string(grid.info.ny) + "x" + std::to_string(grid.info.nz);
        if (kernels_ && kernels_->pe_layout == PeLayout::Lanes && !otherLayoutAffordable(grid))
          continue;  // as in expectAllAgree
        // As the renderer calls it: small batches fall back to the lists.
        const KernelOptions options = kernels_ ? *kernels_ : KernelOptions{};
        GridRtIntersector plain(*runtime_, grid, PeInterrupt::Off, options);
        plain.intersectTowardsPoint(light, rays, HitMode::Closest, got);
        EXPECT_EQ(test::hitMismatches(want, got, where + " towards the light"), 0u);
        GridRtIntersector gridrt(*runtime_, grid, PeInterrupt::Off, options);
        gridrt.forceLightBundles();
        gridrt.intersectTowardsPoint(light, rays, HitMode::Closest, got);
        EXPECT_EQ(test::hitMismatches(want, got, where + " light bundles"), 0u);
        gridrt.intersectTowardsPoint(light, rays, HitMode::AnyHit, got);
        size_t differ = 0;
        for (size_t i = 0; i < rays.size(); ++i)
          differ += (got[i].prim >= 0) != (want[i].prim >= 0);
        EXPECT_EQ(differ, 0u) << where << " light bundles any-hit";
        if (kernels_ || !otherLayoutAffordable(grid)) continue;
        GridRtIntersector other(*runtime_, grid, PeInterrupt::Off, otherChoices());
        other.forceLightBundles();
        other.intersectTowardsPoint(light, rays, HitMode::Closest, got);
        EXPECT_EQ(
            test::hitMismatches(want, got, where + " other layout and transfer light bundles"), 0u);
      }
    }
  }

  void checkScene(const Scene& scene, const std::string& label, int w, int h) {
    auto tris = prepareTriangles(scene);
    Bounds b = sceneBounds(scene);
    Camera camera = cameraOf(scene);
    PinholeView view = PinholeView::of(camera, w, h, PixelWindow{});
    std::vector<GrRay> rays = cameraRays(scene, w, h);
    std::vector<GridSettings> grids = standardGrids(b, tris.size());
    expectAllAgree(tris, b, rays, grids, label, camera.orthographic ? nullptr : &view);
    expectLightPathAgrees(tris, b, rays, grids, label);
  }

  std::unique_ptr<ClRuntime> runtime_;
  // The kernels a parameterised test (Conformance) names; none: the device's default
  // and, beside it, the other layout and transfer.
  std::optional<KernelOptions> kernels_;
};

// The targeted cases, small grids of few triangles a PE, run with each PE layout and each
// batch transfer (the lane kernels too on a CPU device: fast on PEs this small). The
// tests of whole scenes stay ConformanceFixture's, which run the default kernels and the other
// layout with the other transfer where affordable: the lane kernels cull nothing and are
// brute force on a scene's big PEs (minutes on a CPU), and each rule they check is checked
// for all four here on the small grids.
class Conformance : public ConformanceFixture,
                    public ::testing::WithParamInterface<test::KernelChoice> {
 protected:
  void SetUp() override {
    ConformanceFixture::SetUp();
    if (IsSkipped()) return;
    kernels_ = GetParam().options();
  }
};

INSTANTIATE_TEST_SUITE_P(Kernels, Conformance, test::kernelChoices(), test::kernelChoiceName);

TEST_P(Conformance, BunnyRes4AtThePapersGridsMatchesBruteOnEveryPixel) {
  Scene scene = loadGltfFile(test::modelScene("bunny_res4.glb"));
  auto tris = prepareTriangles(scene);
  std::vector<GridSettings> grids;
  for (int n : {1, 2, 3, 4, 5, 6}) {
    GridSettings s;
    s.automatic = false;
    s.dims = {n, n, n};
    grids.push_back(s);
  }
  grids.push_back(GridSettings{});
  PinholeView view = PinholeView::of(scene.camera, 320, 240, PixelWindow{});
  expectAllAgree(tris, sceneBounds(scene), cameraRays(scene, 320, 240), grids, "bunny_res4", &view);
}

// Phase 2's per-ray diagnostics on the list path, where each thread picks its rays' lanes
// out of the packets' masks: the same list lengths, tests and winning PEs as the camera
// path, which reads them per bundle lane. With the interrupt, rays from the side of the
// lowest PEs (the first tasks): the winners stay, and so do the rays' tests (those of
// their PEs up to the winner, ray_tests.h), whatever the interrupt skipped; the batch
// counts at least those. The camera path reads the PEs'
// hulls (pe_hulls.h), which rays over a PE's empty corners miss, so it is compared with
// hulls equal to the boxes, and with its own hulls a ray's lanes are a subset of its list.
TEST_P(Conformance, ListPathDiagnosticsAgreeWithTheCameraPathAndTheCounters) {
  Scene scene = loadGltfFile(test::modelScene("bunny_res4.glb"));
  auto tris = prepareTriangles(scene);
  const Bounds b = sceneBounds(scene);
  UniformGrid grid = buildUniformGrid(tris, b, GridSettings{});
  const int w = 160, h = 120;
  PinholeView view = PinholeView::of(scene.camera, w, h, PixelWindow{});
  std::vector<GrRay> rays = cameraRays(scene, w, h);
  struct BothPaths {
    RayDiagnostics list, camera;
    std::vector<GrHit> list_hits, camera_hits;
  };
  auto bothPaths = [&](GridRtIntersector& x) {
    BothPaths p;
    x.intersect(rays, HitMode::Closest, p.list_hits, &p.list);
    x.intersectPrimary(view, rays, p.camera_hits, &p.camera);
    EXPECT_EQ(test::hitMismatches(p.camera_hits, p.list_hits, "list path"), 0u);
    EXPECT_EQ(p.list.winning_pe, p.camera.winning_pe);
    return p;
  };
  {
    GridRtIntersector hulls(*runtime_, grid, PeInterrupt::Off, *kernels_);
    const BothPaths p = bothPaths(hulls);
    size_t fewer = 0;
    for (size_t r = 0; r < rays.size(); ++r) {
      EXPECT_LE(p.camera.list_length[r], p.list.list_length[r]) << "ray " << r;
      fewer += p.camera.list_length[r] < p.list.list_length[r];
    }
    EXPECT_GT(fewer, 0u);
  }
  grid.pe_hull = grid.pe_box;
  GridRtIntersector plain(*runtime_, grid, PeInterrupt::Off, *kernels_);
  const BothPaths p = bothPaths(plain);
  EXPECT_EQ(p.list.list_length, p.camera.list_length);
  EXPECT_EQ(p.list.tests, p.camera.tests);
  size_t hit_count = 0;
  for (const GrHit& hit : p.list_hits) hit_count += hit.prim >= 0;
  EXPECT_GT(hit_count, rays.size() / 10);

  // From below the grid's lowest z (voxel index, hence PE order, grows with z) upwards.
  const glm::vec3 lo = b.lo, size = b.extent();
  const glm::vec3 eye(lo.x + 0.5f * size.x, lo.y + 0.5f * size.y, lo.z - size.z);
  std::vector<GrRay> up;
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i) {
      const glm::vec3 target(lo.x + size.x * (i + 0.5f) / w, lo.y + size.y * (j + 0.5f) / h,
                             lo.z + 2.0f * size.z);
      const glm::vec3 d = glm::normalize(target - eye);
      up.push_back(GrRay{eye.x, eye.y, eye.z, 0.0f, d.x, d.y, d.z, kInf});
    }
  RayDiagnostics all, skipping;
  std::vector<GrHit> all_hits, skipping_hits;
  plain.intersect(up, HitMode::Closest, all_hits, &all);
  GridRtIntersector interrupt(*runtime_, grid, PeInterrupt::AllRays, *kernels_);
  interrupt.intersect(up, HitMode::Closest, skipping_hits, &skipping);
  EXPECT_EQ(test::hitMismatches(all_hits, skipping_hits, "interrupt"), 0u);
  EXPECT_EQ(skipping.winning_pe, all.winning_pe);
  EXPECT_EQ(skipping.list_length, all.list_length);
  EXPECT_EQ(skipping.tests, all.tests);
  uint64_t sum = 0;
  for (int tests : skipping.tests) sum += uint64_t(tests);
  // How many it skips depends on the order the work-groups run in (interrupt_order_test
  // checks that in order it skips); which hits it keeps, and the rays' tests, do not.
  EXPECT_LE(sum, interrupt.counters().tests);
  EXPECT_GT(sum, 0u);
}

// The `tests` AOV against its definition, worked out here in double precision from the
// voxels alone: per ray, the triangles of every PE whose voxel the ray enters no later
// than its winning PE's (all it pierces on a miss). Both paths, interrupt on: the list
// path in list order, the camera path (hulls equal to the boxes) by its pierced lanes.
TEST_P(Conformance, TestsAovCountsThePesUpToTheWinner) {
  Scene scene = loadGltfFile(test::modelScene("bunny_res4.glb"));
  auto tris = prepareTriangles(scene);
  UniformGrid grid = buildUniformGrid(tris, sceneBounds(scene), GridSettings{});
  grid.pe_hull = grid.pe_box;
  const int w = 160, h = 120;
  PinholeView view = PinholeView::of(scene.camera, w, h, PixelWindow{});
  std::vector<GrRay> rays = cameraRays(scene, w, h);
  GridRtIntersector x(*runtime_, grid, PeInterrupt::AllRays, *kernels_);
  RayDiagnostics list, camera;
  std::vector<GrHit> list_hits, camera_hits;
  x.intersect(rays, HitMode::Closest, list_hits, &list);
  x.intersectPrimary(view, rays, camera_hits, &camera);
  ASSERT_EQ(list.winning_pe, camera.winning_pe);
  // Where the ray enters PE pe's voxel within [tmin, tmax], or NaN where it misses it.
  auto entry = [&](const GrRay& ray, int pe) {
    const float* box = &grid.pe_box[size_t(pe) * 6];  // lo x, y, z then hi x, y, z
    const double o[3] = {ray.ox, ray.oy, ray.oz}, d[3] = {ray.dx, ray.dy, ray.dz};
    double t0 = ray.tmin, t1 = ray.tmax;
    for (int a = 0; a < 3; ++a) {
      if (d[a] == 0.0) {
        if (o[a] < box[a] || o[a] > box[3 + a]) return std::nan("");
        continue;
      }
      const double near = (box[a] - o[a]) / d[a], far = (box[3 + a] - o[a]) / d[a];
      t0 = std::max(t0, std::min(near, far));
      t1 = std::min(t1, std::max(near, far));
    }
    return t0 <= t1 ? t0 : std::nan("");
  };
  size_t hits = 0, list_off = 0, camera_off = 0;
  for (size_t r = 0; r < rays.size(); ++r) {
    const int winner = list.winning_pe[r];
    hits += winner >= 0;
    const double winner_entry = winner >= 0 ? entry(rays[r], winner) : 0.0;
    int want = 0;
    for (int pe = 0; pe < grid.peCount(); ++pe) {
      const double t = entry(rays[r], pe);
      if (!std::isnan(t) && (winner < 0 || t <= winner_entry)) want += grid.triangleCountOfPe(pe);
    }
    list_off += list.tests[r] != want;
    camera_off += camera.tests[r] != want;
  }
  EXPECT_GT(hits, rays.size() / 10);
  EXPECT_EQ(list_off, 0u) << "list path";
  EXPECT_EQ(camera_off, 0u) << "camera path";
}

// Whole scenes: the default kernels and the other layout with the other transfer (below
// kOtherLayoutMaxMeanPeTriangles a PE); Conformance holds each rule to all four.
class SharedScenes : public ConformanceFixture,
                     public ::testing::WithParamInterface<const char*> {};

TEST_P(SharedScenes, EveryPixelMatchesBruteAtEveryGrid) {
  Scene scene = loadGltfFile(test::modelScene(GetParam()));
  // Large meshes at a smaller image keep CI time bounded; every pixel is still compared.
  bool large = scene.triangleCount() > 20000;
  checkScene(scene, GetParam(), large ? 160 : 320, large ? 120 : 240);
}

INSTANTIATE_TEST_SUITE_P(Conformance, SharedScenes,
                         ::testing::Values("bunny_res4.glb", "bunny_res3.glb", "bunny_res2.glb",
                                           "bunny.glb", "teapot.glb", "loader_test.glb",
                                           "OrientationTest.glb", "TransmissionRoughnessTest.glb"),
                         [](const auto& info) {
                           std::string n = info.param;
                           return n.substr(0, n.find('.'));
                         });

// Whole scenes, as SharedScenes.
class ProjectScenes : public ConformanceFixture,
                      public ::testing::WithParamInterface<const char*> {};

TEST_P(ProjectScenes, EveryPixelMatchesBruteAtEveryGrid) {
  Scene scene = loadGltfFile(test::sourcePath(std::string("scenes/") + GetParam()));
  checkScene(scene, GetParam(), 320, 240);
}

INSTANTIATE_TEST_SUITE_P(Conformance, ProjectScenes,
                         ::testing::Values("default.gltf", "quad_light.gltf",
                                           "refraction_slab.gltf", "mirror_test.gltf"),
                         [](const auto& info) {
                           std::string n = info.param;
                           return n.substr(0, n.find('.'));
                         });

// Packet culling (host/gridrt/culling/packet_culling.h) on the camera path, where its argument is
// most strained: cameras inside the bunny (triangles straddle the camera plane, some nearly
// edge-on, very close to the eye) and one grazing its surface, for both triangle tests.
// Packet culling is the packet kernels' own (the lane kernels cull nothing): default kernels.
TEST_F(ConformanceFixture, CameraPathWithPacketCullingFromInsideAndGrazing) {
  Scene scene = loadGltfFile(test::modelScene("bunny_res2.glb"));
  const Bounds b = sceneBounds(scene);
  const glm::vec3 c = b.center(), e = b.extent();
  const Camera cameras[] = {
      lookAtCamera(c, c + glm::vec3(0, 0, -1), 1.4f),
      lookAtCamera(c, c + glm::vec3(1, 0.3f, 0.2f), 0.9f),
      lookAtCamera(c + glm::vec3(0.3f, -0.2f, 0.1f) * e, c + glm::vec3(0, 1, 0) * e, 1.2f),
      // Along the top of the box, looking across the back: grazing the surface.
      lookAtCamera(c + glm::vec3(-0.6f, 0.05f, 0.0f) * e, c + glm::vec3(0.6f, 0.05f, 0.0f) * e,
                   0.5f)};
  const int w = 160, h = 120;
  for (bool watertight : {false, true}) {
    KernelOptions options;
    options.watertight = watertight;
    const auto tris = prepareTriangles(scene, options);
    BruteIntersector brute(*runtime_, tris, options);
    const UniformGrid grid = buildUniformGrid(tris, b, GridSettings{});
    GridRtIntersector gridrt(*runtime_, grid, PeInterrupt::Off, options);
    for (size_t k = 0; k < std::size(cameras); ++k) {
      std::vector<GrRay> rays;
      for (int j = 0; j < h; ++j)
        for (int i = 0; i < w; ++i) rays.push_back(cameraRay(cameras[k], w, h, i, j, 0.5f, 0.5f));
      const PinholeView view = PinholeView::of(cameras[k], w, h, PixelWindow{});
      std::vector<GrHit> want, got;
      brute.intersect(rays, HitMode::Closest, want, nullptr);
      gridrt.intersectPrimary(view, rays, got, nullptr);
      size_t hits = 0;
      for (const GrHit& hit : want) hits += hit.prim >= 0;
      EXPECT_GT(hits, rays.size() / 10) << "camera " << k;
      EXPECT_EQ(test::hitMismatches(
                    want, got,
                    std::string(watertight ? "watertight" : "mt") + " camera " + std::to_string(k)),
                0u);
    }
  }
}

// The camera path that makes its own rays (GridRtIntersector::generateAndIntersectPrimary,
// which writes them to the bundle planes band by band and counts the frame's cover from
// the planes) against the interface's plain version (make the rays, then trace them) on
// brute force: the same rays bit for bit and the same hits, for whole images and windows
// with partial tiles, a field of view so wide that packet culling must stay off, and an
// orthographic camera (no common eye: the plain version).
// The host's ray generation and culling decision, whatever the kernels: default kernels.
TEST_F(ConformanceFixture, CameraPathThatMakesItsRaysMatchesBrute) {
  Scene scene = loadGltfFile(test::modelScene("bunny_res2.glb"));
  const Bounds b = sceneBounds(scene);
  const glm::vec3 c = b.center(), e = b.extent();
  Camera wide = lookAtCamera(c + glm::vec3(0.0f, 0.2f, 1.5f) * e, c, 3.0f);  // ~172 degrees
  Camera ortho = defaultCamera(b);
  ortho.orthographic = true;
  ortho.ymag = 0.6f * e.y;
  const Camera cameras[] = {
      defaultCamera(b), lookAtCamera(c + glm::vec3(0.8f, 0.3f, 0.9f) * e, c, 0.7f), wide, ortho};
  const PixelWindow windows[] = {PixelWindow{0, 0, 0, 0}, PixelWindow{13, 7, 150, 101}};
  const int w = 160, h = 120;
  const auto tris = prepareTriangles(scene);
  BruteIntersector brute(*runtime_, tris);
  const UniformGrid grid = buildUniformGrid(tris, b, GridSettings{});
  GridRtIntersector gridrt(*runtime_, grid, PeInterrupt::Off);
  size_t hits = 0;
  for (size_t k = 0; k < std::size(cameras); ++k) {
    for (const PixelWindow& window : windows) {
      const PinholeView view = PinholeView::of(cameras[k], w, h, window);
      const CameraRayGenerator camera(cameras[k], w, h);
      std::vector<GrRay> want_rays, got_rays;
      std::vector<GrHit> want, got;
      brute.generateAndIntersectPrimary(view, camera, want_rays, want, nullptr);
      gridrt.generateAndIntersectPrimary(view, camera, got_rays, got, nullptr);
      const std::string where = "camera " + std::to_string(k) + " window " +
                                std::to_string(view.window.width()) + "x" +
                                std::to_string(view.window.height());
      ASSERT_EQ(got_rays.size(), want_rays.size()) << where;
      EXPECT_EQ(std::memcmp(got_rays.data(), want_rays.data(), want_rays.size() * sizeof(GrRay)), 0)
          << where;
      EXPECT_EQ(test::hitMismatches(want, got, where), 0u);
      // Culling where the frame covers every ray (kCullMinCos), never past it.
      const bool pinhole = k != 3, covered = k != 2;
      if (pinhole) {
        EXPECT_EQ(gridrt.packetCullingUsed(), covered) << where;
      }
      for (const GrHit& hit : want) hits += hit.prim >= 0;
    }
  }
  EXPECT_GT(hits, size_t(w * h));
}

// A whole scene, as SharedScenes: the default kernels and the other layout and transfer.
TEST_F(ConformanceFixture, BuiltInDefaultSceneMatchesBrute) {
  checkScene(makeDefaultScene(), "default scene", 320, 240);
}

// Random rays: origins inside and outside the grid, all directions, with a share of
// axis-parallel directions including -0.0 components.
std::vector<GrRay> randomRays(const Bounds& b, size_t count, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  std::normal_distribution<float> gauss;
  glm::vec3 c = b.center(), e = b.extent();
  std::vector<GrRay> rays;
  for (size_t k = 0; k < count; ++k) {
    // Half inside the box, half in a box three times larger around it.
    float spread = k % 2 ? 3.0f : 1.0f;
    glm::vec3 o = c + (glm::vec3(unit(rng), unit(rng), unit(rng)) - 0.5f) * e * spread;
    glm::vec3 d;
    if (k % 5 == 0) {
      int axis = int(k / 5) % 3;
      float sign = (k / 15) % 2 ? 1.0f : -1.0f;
      d = glm::vec3(((k / 30) % 2) ? -0.0f : 0.0f);
      d[axis] = sign;
    } else {
      do d = glm::vec3(gauss(rng), gauss(rng), gauss(rng));
      while (glm::length(d) < 1e-3f);
      d = glm::normalize(d);
    }
    rays.push_back(GrRay{o.x, o.y, o.z, 0.0f, d.x, d.y, d.z, kInf});
  }
  return rays;
}

TEST_P(Conformance, RandomRaysInsideAndOutsideTheGridMatchBrute) {
  Scene scene = loadGltfFile(test::modelScene("bunny_res4.glb"));
  auto tris = prepareTriangles(scene);
  Bounds b = sceneBounds(scene);
  expectAllAgree(tris, b, randomRays(b, 20000, 7), standardGrids(b, tris.size()), "random");
}

// The same model moved far from the world origin: the margin's scale is the longest way of
// a ray through the grid, not the coordinates (kGridMarginRel), so at x = 10^4 the margin
// stays 1e-5 of the model's diagonal (2e-6) while positions round by ulps of 1e-3. The
// same random rays (inside, outside, axis-parallel) must still find every hit.
TEST_P(Conformance, RandomRaysAroundAModelFarFromTheOriginMatchBrute) {
  for (float offset : {1e2f, 1e3f, 1e4f}) {
    Scene scene = loadGltfFile(test::modelScene("bunny_res4.glb"));
    for (glm::vec3& p : scene.positions) p += glm::vec3(offset, -0.5f * offset, 0.25f * offset);
    auto tris = prepareTriangles(scene);
    Bounds b = sceneBounds(scene);
    const std::vector<GridSettings> grids = standardGrids(b, tris.size());
    EXPECT_LT(buildUniformGrid(tris, b, grids.front()).margin,
              1e-5 * glm::length(b.extent()) * 1.01)
        << offset;
    const std::vector<GrRay> rays = randomRays(b, 20000, 7);
    expectAllAgree(tris, b, rays, grids, "far " + std::to_string(int(offset)));
    // The adaptive structure, two levels deep: its sub-grids' float planes are walked too.
    GridSettings adaptive;
    adaptive.structure = GridStructure::Adaptive;
    adaptive.max_leaf_triangles = 16;
    BruteIntersector brute(*runtime_, tris);
    const UniformGrid grid = buildGrid(tris, b, adaptive);
    ASSERT_GE(grid.adaptive.depth, 1) << offset;
    GridRtIntersector gridrt(*runtime_, grid, PeInterrupt::Off, *kernels_);
    std::vector<GrHit> want, got;
    brute.intersect(rays, HitMode::Closest, want, nullptr);
    gridrt.intersect(rays, HitMode::Closest, got, nullptr);
    EXPECT_EQ(test::hitMismatches(want, got, "far adaptive " + std::to_string(int(offset))), 0u);
  }
}

TEST_P(Conformance, RandomRaysInTheClosedDefaultBoxMatchBrute) {
  Scene scene = makeDefaultScene();
  auto tris = prepareTriangles(scene);
  Bounds b = sceneBounds(scene);
  expectAllAgree(tris, b, randomRays(b, 20000, 11), standardGrids(b, tris.size()), "box");
}

// ---- Targeted cases -------------------------------------------------------------------

using test::tri;

Bounds boundsOf(const std::vector<GrTriangle>& tris) {
  Bounds b;
  for (const auto& t : tris) {
    glm::vec3 a(t.v0x, t.v0y, t.v0z);
    b.grow(a);
    b.grow(a + glm::vec3(t.e1x, t.e1y, t.e1z));
    b.grow(a + glm::vec3(t.e2x, t.e2y, t.e2z));
  }
  return b;
}

GridSettings dims(int x, int y, int z) {
  GridSettings s;
  s.automatic = false;
  s.dims = {x, y, z};
  return s;
}

GrRay ray(glm::vec3 o, glm::vec3 d) {
  d = glm::normalize(d);
  return GrRay{o.x, o.y, o.z, 0.0f, d.x, d.y, d.z, kInf};
}

TEST_P(Conformance, BigTriangleWhoseHitLiesInALaterVoxelLosesToACloserSmallOne) {
  // A big slanted triangle overlaps the first voxel the ray enters, but the ray meets it
  // only in the last voxel; a small triangle in the middle voxel is closer. Without the
  // in-voxel rule the first PE would report the big triangle and win.
  std::vector<GrTriangle> tris = {
      tri({-1, -1, -4}, {4, -1, 0.5f}, {-1, 4, 0.5f}, 0),  // big, slanted
      tri({-0.2f, -0.2f, -1.5f}, {0.2f, -0.2f, -1.5f}, {0.0f, 0.2f, -1.5f}, 1),
      tri({3.9f, 3.9f, -3.9f}, {4, 3.9f, -3.9f}, {3.9f, 4, -3.9f}, 2)};  // stretches the box
  Bounds b = boundsOf(tris);
  std::vector<GrRay> rays = {ray({0.0f, 0.0f, 1.0f}, {0, 0, -1}),
                             ray({0.05f, 0.05f, 1.0f}, {0.01f, 0.0f, -1})};
  expectAllAgree(tris, b, rays, {dims(1, 1, 4), dims(3, 3, 3), dims(1, 1, 16)}, "big");
  UniformGrid grid = buildUniformGrid(tris, b, dims(1, 1, 4));
  GridRtIntersector gridrt(*runtime_, grid, PeInterrupt::Off, *kernels_);
  std::vector<GrHit> hits;
  gridrt.intersect(rays, HitMode::Closest, hits, nullptr);
  EXPECT_EQ(hits[0].prim, 1);
}

// The in-voxel rule, seen in the winner: phase 2 keeps the smallest (t, prim) whatever the
// rule, but only with it does the PE of the voxel where the hit lies report it. Rays going
// up meet the big slanted triangle in the third of four voxels; it overlaps the first one
// too (a lower PE), which without the rule reports the same hit and is named the winner.
TEST_P(Conformance, AHitIsWonByThePeOfTheVoxelItLiesIn) {
  std::vector<GrTriangle> tris = {tri({-1, -1, -4}, {4, -1, 0.5f}, {-1, 4, 0.5f}, 0)};
  Bounds b = boundsOf(tris);
  UniformGrid grid = buildUniformGrid(tris, b, dims(1, 1, 4));
  std::vector<GrRay> rays;
  for (int j = 0; j < 8; ++j)
    for (int i = 0; i < 8; ++i)
      rays.push_back(ray({-0.5f + 0.2f * i, -0.5f + 0.2f * j, -5.0f}, {0, 0, 1}));
  for (PeInterrupt interrupt : {PeInterrupt::Off, PeInterrupt::AllRays}) {
    GridRtIntersector gridrt(*runtime_, grid, interrupt, *kernels_);
    std::vector<GrHit> hits;
    RayDiagnostics diagnostics;
    gridrt.intersect(rays, HitMode::Closest, hits, &diagnostics);
    size_t checked = 0;
    for (size_t r = 0; r < rays.size(); ++r) {
      ASSERT_EQ(hits[r].prim, 0) << "ray " << r;
      const float z = rays[r].oz + hits[r].t * rays[r].dz;
      glm::vec3 lo, hi;
      grid.voxelBoxOfPe(diagnostics.winning_pe[r], lo, hi);
      EXPECT_TRUE(lo.z <= z && z <= hi.z) << gridrt.name() << " ray " << r << ": hit at z " << z
                                          << " won by the PE of [" << lo.z << ", " << hi.z << "]";
      checked += z > grid.info.minz + 1.5f * grid.info.cellz;  // beyond the first two voxels
    }
    EXPECT_GT(checked, rays.size() / 2) << "the hits should lie beyond the first voxels";
  }
}

TEST_P(Conformance, RaysThroughVoxelEdgesAndCornersAreNotMissed) {
  // A 4x4x4 grid over [0,4]^3 with unit cells (the triangles pin the box); rays along
  // voxel edges and through voxel corners hit triangles sitting on those edges/corners.
  std::vector<GrTriangle> tris = {tri({0, 0, 0}, {0.01f, 0, 0}, {0, 0.01f, 0}, 0),
                                  tri({4, 4, 4}, {3.99f, 4, 4}, {4, 3.99f, 4}, 1),
                                  tri({1.5f, 2, 2}, {2.5f, 2, 2}, {2, 2, 3}, 2),
                                  tri({1, 1, 1}, {3, 1, 3}, {1, 3, 3}, 3)};
  Bounds b = boundsOf(tris);
  std::vector<GrRay> rays;
  for (float x : {1.0f, 2.0f, 3.0f})
    for (float y : {1.0f, 2.0f, 3.0f}) {
      rays.push_back(ray({x, y, 10.0f}, {0, 0, -1}));  // along a voxel edge
      rays.push_back(ray({x, -1.0f, y}, {0, 1, 0}));
    }
  rays.push_back(ray({-1, -1, -1}, {1, 1, 1}));  // through every corner
  rays.push_back(ray({5, 5, 5}, {-1, -1, -1}));
  rays.push_back(ray({2, 2, 10}, {0, 0, -1}));  // hits the edge-on triangle's edge
  expectAllAgree(tris, b, rays, {dims(4, 4, 4), dims(2, 2, 2), dims(8, 8, 8)}, "edges");
}

TEST_P(Conformance, TriangleInAVoxelBoundaryPlaneIsFoundFromBothSides) {
  // The plane z = 2 is a voxel boundary of the 4x4x4 grid over [0,4]^3.
  std::vector<GrTriangle> tris = {tri({0, 0, 0}, {0.01f, 0, 0}, {0, 0.01f, 0}, 0),
                                  tri({4, 4, 4}, {3.99f, 4, 4}, {4, 3.99f, 4}, 1),
                                  tri({0.5f, 0.5f, 2}, {3.5f, 0.5f, 2}, {0.5f, 3.5f, 2}, 2)};
  Bounds b = boundsOf(tris);
  std::vector<GrRay> rays;
  for (int k = 0; k < 50; ++k) {
    float x = 0.6f + 0.03f * k, y = 0.7f + 0.02f * k;  // inside the triangle (x + y < 4)
    rays.push_back(ray({x, y, 10}, {0, 0, -1}));
    rays.push_back(ray({x, y, -10}, {0.01f, 0, 1}));
  }
  expectAllAgree(tris, b, rays, {dims(4, 4, 4), dims(1, 1, 2), dims(8, 8, 8)}, "plane");
  UniformGrid grid = buildUniformGrid(tris, b, dims(4, 4, 4));
  GridRtIntersector gridrt(*runtime_, grid, PeInterrupt::Off, *kernels_);
  std::vector<GrHit> hits;
  gridrt.intersect(rays, HitMode::Closest, hits, nullptr);
  for (const auto& h : hits) EXPECT_EQ(h.prim, 2);
}

TEST_P(Conformance, RayStartingOnAVoxelFaceAndInsideTheGrid) {
  std::vector<GrTriangle> tris = {tri({0, 0, 0}, {4, 0, 0}, {0, 4, 0}, 0),
                                  tri({0, 0, 4}, {4, 0, 4}, {0, 4, 4}, 1),
                                  tri({0, 0, 0}, {0, 4, 0}, {0, 0, 4}, 2)};
  Bounds b = boundsOf(tris);
  std::vector<GrRay> rays;
  for (float z : {1.0f, 2.0f, 3.0f}) {  // on voxel faces of the 4x4x4 grid
    rays.push_back(ray({1, 1, z}, {0, 0, -1}));
    rays.push_back(ray({1, 1, z}, {0, 0, 1}));
    rays.push_back(ray({1, 1, z}, {-1, 0.1f, 0.1f}));
  }
  rays.push_back(ray({0.5f, 0.5f, 0.5f}, {-1, -1, -1}));  // inside, towards the corner
  expectAllAgree(tris, b, rays, {dims(4, 4, 4), dims(3, 3, 3)}, "face");
}

TEST_P(Conformance, EveryTriangleInOneVoxel) {
  std::vector<GrTriangle> tris;
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(0.0f, 0.1f);
  for (int k = 0; k < 200; ++k)
    tris.push_back(
        tri({u(rng), u(rng), u(rng)}, {u(rng), u(rng), u(rng)}, {u(rng), u(rng), u(rng)}, k));
  // Pin the box far away so that the cluster sits inside one voxel of a 4x4x4 grid.
  tris.push_back(tri({10, 10, 10}, {10.01f, 10, 10}, {10, 10.01f, 10}, 200));
  Bounds b = boundsOf(tris);
  UniformGrid grid = buildUniformGrid(tris, b, dims(4, 4, 4));
  EXPECT_EQ(grid.peCount(), 2);
  std::vector<GrRay> rays = randomRays(Bounds{glm::vec3(0), glm::vec3(0.1f)}, 2000, 5);
  expectAllAgree(tris, b, rays, {dims(4, 4, 4)}, "cluster");
}

// Closest hits through light bundles (forced, whatever the batch) on a fixed grid, against
// brute force; at least `blocked` rays must hit an occluder (triangles from index 2 on),
// or the case tests nothing.
size_t lightBundleMismatches(ClRuntime& runtime, const std::vector<GrTriangle>& tris,
                             const std::vector<GrRay>& rays, glm::vec3 light, glm::ivec3 dims,
                             size_t blocked, const KernelOptions& options) {
  BruteIntersector brute(runtime, tris);
  std::vector<GrHit> want, got;
  brute.intersect(rays, HitMode::Closest, want, nullptr);
  size_t occluded = 0;
  for (const GrHit& h : want) occluded += h.prim >= 2;
  EXPECT_GE(occluded, blocked);
  GridSettings settings;
  settings.automatic = false;
  settings.dims = dims;
  UniformGrid grid = buildUniformGrid(tris, boundsOf(tris), settings);
  GridRtIntersector gridrt(runtime, grid, PeInterrupt::Off, options);
  gridrt.forceLightBundles();
  gridrt.intersectTowardsPoint(light, rays, HitMode::Closest, got);
  return test::hitMismatches(want, got, "light bundles");
}

// Light bundles assume each shadow ray ends at the light. Rays moved sideways by far more
// than a cube cell (1.0 against cells of ~0.02 at the occluders) must still meet their
// occluders: the voxels are grown by the rays' measured miss (kLightSlackFactor); with the
// factor at 0 these rays fall outside the occluders' footprints and get through.
TEST_P(Conformance, LightBundlesCoverRaysThatMissTheLight) {
  const glm::vec3 light(0.0f, 2.0f, 0.0f);
  std::vector<GrTriangle> tris = {tri({-3, 0, -3}, {3, 0, -3}, {3, 0, 3}, 0),
                                  tri({-3, 0, -3}, {3, 0, 3}, {-3, 0, 3}, 1)};
  std::vector<GrRay> rays;
  for (int k = 0; k < 4096; ++k) {
    // A small occluder at height 1 above where each shifted ray passes.
    float x = -1.5f + 3.0f * float(k % 64) / 63.0f, z = -1.5f + 3.0f * float(k / 64) / 63.0f;
    glm::vec3 p(x * 0.2f, 0.0f, z * 0.2f);  // the unshifted start, almost under the light
    glm::vec3 d = glm::normalize(light - p);
    glm::vec3 o = p + glm::vec3(x, 0.01f, z) - glm::vec3(x * 0.2f, 0.0f, z * 0.2f);
    glm::vec3 c = o + (1.0f / d.y) * d;  // where the ray crosses y = 1
    tris.push_back(tri(c + glm::vec3(-0.01f, 0, -0.01f), c + glm::vec3(0.01f, 0, -0.01f),
                       c + glm::vec3(0, 0, 0.01f), int(tris.size())));
    rays.push_back(GrRay{o.x, o.y, o.z, 0.0f, d.x, d.y, d.z, glm::length(light - p)});
  }
  EXPECT_EQ(
      lightBundleMismatches(*runtime_, tris, rays, light, {12, 4, 12}, rays.size(), *kernels_), 0u);
}

// A light on a grid vertex, with occluders in the eight voxels around it, close to the
// light: no box there can be projected onto the cube, so each receives every ray.
TEST_P(Conformance, LightBundlesWithTheLightOnAGridVertex) {
  std::vector<GrTriangle> tris = {tri({-2, -2, -2}, {2, -2, -2}, {2, -2, 2}, 0),
                                  tri({-2, 2, 2}, {2, 2, 2}, {-2, 2, -2}, 1)};
  const glm::vec3 light(0.0f, 0.0f, 0.0f);  // a vertex of the 4x4x4 grid over [-2, 2]^3
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  for (int k = 0; k < 8; ++k) {
    glm::vec3 c(k & 1 ? 0.05f : -0.05f, k & 2 ? 0.05f : -0.05f, k & 4 ? 0.05f : -0.05f);
    tris.push_back(tri(c + glm::vec3(-0.04f, 0, 0), c + glm::vec3(0.04f, 0, 0.01f),
                       c + glm::vec3(0, 0.04f, -0.02f), int(tris.size())));
  }
  std::vector<GrRay> rays;
  for (int k = 0; k < 4000; ++k) {
    glm::vec3 o(u(rng) * 1.9f, u(rng) * 1.9f, u(rng) * 1.9f);
    glm::vec3 d = glm::normalize(light - o);
    rays.push_back(GrRay{o.x, o.y, o.z, 0.0f, d.x, d.y, d.z, glm::length(light - o)});
  }
  EXPECT_EQ(lightBundleMismatches(*runtime_, tris, rays, light, {4, 4, 4}, 50, *kernels_), 0u);
}

// The light bundles hand a PE every ray whose line may pass the part of its voxel its
// triangles fill (pe_hulls.h), and the kernel's slab test keeps the (ray, PE) pairs of the
// traversal lists there: with every voxel filled, PE by PE as many pairs as the list path
// walks. Half the rays have an exact zero in their direction, towards a light that lies
// inside a column of voxels, 1 % of a voxel from the next: their cube cells overlap the
// neighbouring columns' outlines, so those PEs receive them, and only the slab test's rule
// for a zero direction (inside the slab for every t or for none) keeps them out.
// The host's pairs of the light bundles, for both layouts (the transfer moves no pairs).
TEST_F(ConformanceFixture, LightBundlesKeepTheListsPairsForRaysAlongAGridAxis) {
  const int n = 8;
  std::vector<GrTriangle> lattice;
  for (int z = 0; z < n; ++z)
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x) {
        const glm::vec3 c{float(x), float(y), float(z)};  // a triangle spanning its cell
        lattice.push_back(tri(c, c + glm::vec3(1.0f, 1.0f, 0.5f), c + glm::vec3(0.5f, 0.0f, 1.0f),
                              int(lattice.size())));
      }
  Bounds box;
  box.grow(glm::vec3(0.0f));
  box.grow(glm::vec3(float(n)));
  UniformGrid grid = buildUniformGrid(lattice, box, dims(n, n, n));
  ASSERT_EQ(grid.peCount(), n * n * n);
  const glm::vec3 light(3.99f, 3.0f * n, 4.99f);
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(0.05f, n - 0.05f);
  std::vector<GrRay> rays;
  size_t along_axis = 0;
  for (int k = 0; k < 4096; ++k) {
    // Every fourth ray starts in the light's x plane, every fourth in its z plane.
    glm::vec3 o(k % 4 == 0 ? light.x : u(rng), 0.01f, k % 4 == 1 ? light.z : u(rng));
    const glm::vec3 to = light - o;
    const float distance = glm::length(to);
    const glm::vec3 d = to / distance;
    along_axis += d.x == 0.0f || d.z == 0.0f;
    rays.push_back(GrRay{o.x, o.y, o.z, 0.0f, d.x, d.y, d.z, distance});
  }
  ASSERT_EQ(along_axis, 2048u);
  std::vector<GrHit> hits;
  GridRtIntersector lists(*runtime_, grid, PeInterrupt::Off);
  lists.intersect(rays, HitMode::Closest, hits, nullptr);
  for (const PeLayout layout : {PeLayout::Packets, PeLayout::Lanes})
    for (const bool light_culling : {false, true}) {
      KernelOptions options;
      options.pe_layout = layout;
      GridRtIntersector bundles(*runtime_, grid, PeInterrupt::Off, options);
      bundles.forceLightBundles();
      bundles.allowLightCulling(light_culling);
      bundles.intersectTowardsPoint(light, rays, HitMode::Closest, hits);
      const std::string where = std::string(layout == PeLayout::Packets ? "packets" : "lanes") +
                                (light_culling ? ", light culling" : "");
      size_t differ = 0;
      for (int pe = 0; pe < grid.peCount(); ++pe)
        differ += bundles.raysPerPe()[pe] != lists.raysPerPe()[pe];
      EXPECT_EQ(differ, 0u) << "PEs whose pairs differ: " << where;
      EXPECT_EQ(bundles.counters().list_entries, lists.counters().list_entries) << where;
    }
}

// The kernels count the ray-triangle tests they run (IntersectCounters::tests_run). With
// nothing to cull (PEs of one triangle, below the segment culling's minimum, on the list
// path and the light bundles without light culling; no culling frame) that is every
// tested pair's triangles, the paper's count (IntersectCounters::tests); where light
// culling works on those PEs, and packet and segment culling on camera rays on bunny_res4
// (PEs of up to 52 triangles, through either path), it is less, but never less than one
// test a hit. Culling is the packet kernels' own: they run here on any device.
// The packet kernels' culling counts (the lane kernels cull nothing): packets, named.
TEST_F(ConformanceFixture, TheKernelsCountTheTestsTheyRunAfterCulling) {
  KernelOptions packets;
  packets.pe_layout = PeLayout::Packets;
  std::vector<GrTriangle> lattice;
  const int n = 8;
  for (int z = 0; z < n; ++z)
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x) {
        const glm::vec3 c(x + 0.5f, y + 0.5f, z + 0.5f);  // one small triangle a cell
        lattice.push_back(tri(c + glm::vec3(-0.3f, -0.3f, 0.1f), c + glm::vec3(0.3f, -0.2f, 0.0f),
                              c + glm::vec3(0.0f, 0.3f, -0.1f), int(lattice.size())));
      }
  Bounds box;
  box.grow(glm::vec3(0.0f));
  box.grow(glm::vec3(float(n)));
  UniformGrid grid = buildUniformGrid(lattice, box, dims(n, n, n));
  for (int pe = 0; pe < grid.peCount(); ++pe)
    ASSERT_LT(grid.triangleCountOfPe(pe), kSegmentCullMinTriangles);
  auto hitsOf = [](const std::vector<GrHit>& hits) {
    uint64_t count = 0;
    for (const GrHit& hit : hits) count += hit.prim >= 0;
    return count;
  };
  std::vector<GrHit> hits;
  GridRtIntersector lists(*runtime_, grid, PeInterrupt::Off, packets);
  lists.intersect(randomRays(box, 20000, 3), HitMode::Closest, hits, nullptr);
  EXPECT_GT(hitsOf(hits), 1000u);
  EXPECT_EQ(lists.counters().tests_run, lists.counters().tests) << "list path";
  const glm::vec3 light(0.5f * n, 1.5f * n, 0.5f * n);
  std::vector<GrRay> shadow;
  for (const GrRay& r : randomRays(box, 20000, 5)) {
    const glm::vec3 o(r.ox, r.oy, r.oz), d = glm::normalize(light - o);
    shadow.push_back(GrRay{o.x, o.y, o.z, 0.0f, d.x, d.y, d.z, glm::length(light - o)});
  }
  GridRtIntersector bundles(*runtime_, grid, PeInterrupt::Off, packets);
  bundles.forceLightBundles();
  bundles.allowLightCulling(false);
  bundles.intersectTowardsPoint(light, shadow, HitMode::Closest, hits);
  EXPECT_GT(hitsOf(hits), 1000u);
  EXPECT_EQ(bundles.counters().tests_run, bundles.counters().tests) << "light bundles";
  GridRtIntersector light_culled(*runtime_, grid, PeInterrupt::Off, packets);
  light_culled.forceLightBundles();
  light_culled.intersectTowardsPoint(light, shadow, HitMode::Closest, hits);
  EXPECT_GE(light_culled.counters().tests_run, hitsOf(hits)) << "light culling";
  EXPECT_LT(light_culled.counters().tests_run, light_culled.counters().tests) << "light culling";

  Scene scene = loadGltfFile(test::modelScene("bunny_res4.glb"));
  auto tris = prepareTriangles(scene);
  const Bounds b = sceneBounds(scene);
  UniformGrid bunny_grid = buildUniformGrid(tris, b, GridSettings{});
  PinholeView view = PinholeView::of(scene.camera, 320, 240, PixelWindow{});
  const std::vector<GrRay> camera = cameraRays(scene, 320, 240);
  GridRtIntersector culling(*runtime_, bunny_grid, PeInterrupt::Off, packets);
  for (const bool camera_path : {true, false}) {
    const IntersectCounters before = culling.counters();
    if (camera_path)
      culling.intersectPrimary(view, camera, hits, nullptr);
    else
      culling.intersect(camera, HitMode::Closest, hits, nullptr);
    const uint64_t tests = culling.counters().tests - before.tests;
    const uint64_t run = culling.counters().tests_run - before.tests_run;
    const char* path = camera_path ? "camera path" : "list path";
    EXPECT_GT(hitsOf(hits), 1000u) << path;
    EXPECT_GE(run, hitsOf(hits)) << path;
    EXPECT_LT(run, tests / 2) << path;
  }
}

TEST_P(Conformance, EmptyGridMissesEverything) {
  std::vector<GrTriangle> tris;
  Bounds b{glm::vec3(0), glm::vec3(1)};
  UniformGrid grid = buildUniformGrid(tris, b, dims(3, 3, 3));
  EXPECT_EQ(grid.peCount(), 0);
  GridRtIntersector gridrt(*runtime_, grid, PeInterrupt::Off, *kernels_);
  DdaIntersector dda(*runtime_, grid);
  std::vector<GrRay> rays = randomRays(b, 100, 9);
  std::vector<GrHit> hits;
  gridrt.intersect(rays, HitMode::Closest, hits, nullptr);
  for (const auto& h : hits) EXPECT_LT(h.prim, 0);
  dda.intersect(rays, HitMode::Closest, hits, nullptr);
  for (const auto& h : hits) EXPECT_LT(h.prim, 0);
}

TEST_P(Conformance, RaysParallelToEachAxis) {
  Scene scene = makeDefaultScene();
  auto tris = prepareTriangles(scene);
  Bounds b = sceneBounds(scene);
  std::vector<GrRay> rays;
  glm::vec3 c = b.center(), e = b.extent();
  for (int axis = 0; axis < 3; ++axis)
    for (float sign : {1.0f, -1.0f})
      for (int k = 0; k < 100; ++k) {
        glm::vec3 o = c + (glm::vec3(k % 10, k / 10, (k * 7) % 10) / 9.0f - 0.5f) * e * 0.9f;
        glm::vec3 d(-0.0f);
        d[axis] = sign;
        rays.push_back(GrRay{o.x, o.y, o.z, 0.0f, d.x, d.y, d.z, kInf});
      }
  expectAllAgree(tris, b, rays, standardGrids(b, tris.size()), "axis");
}

// A square of two triangles at z = 0 around `shift` (2 across), and a small triangle
// below it that makes the box deep.
std::vector<GrTriangle> squareOverADeepBox(const glm::vec3& shift) {
  const glm::vec3& s = shift;
  return {tri(s + glm::vec3(-1, -1, 0), s + glm::vec3(1, -1, 0), s + glm::vec3(1, 1, 0), 0),
          tri(s + glm::vec3(-1, -1, 0), s + glm::vec3(1, 1, 0), s + glm::vec3(-1, 1, 0), 1),
          tri(s + glm::vec3(-1, -1, -1), s + glm::vec3(-0.9f, -1, -1), s + glm::vec3(-1, -0.9f, -1),
              2)};
}

// The centre pixels (80 x 80) of a (4/3 height) x height view of `target` from `distance`
// away along an oblique direction (so every ray direction component rounds), and their
// centre rays.
struct CentreOfView {
  Camera camera;
  int width, height;
  std::vector<GrRay> rays;
  PinholeView view;
};
CentreOfView centreOfView(const glm::vec3& target, float distance, float fov_degrees, int height) {
  CentreOfView c;
  c.camera = lookAtCamera(target + glm::normalize(glm::vec3(0.6f, 0.35f, 0.7f)) * distance, target,
                          glm::radians(fov_degrees));
  c.height = height;
  c.width = height * 4 / 3;
  const PixelWindow window{c.width / 2 - 40, height / 2 - 40, c.width / 2 + 40, height / 2 + 40};
  for (int j = window.y0; j < window.y1; ++j)
    for (int i = window.x0; i < window.x1; ++i)
      c.rays.push_back(cameraRay(c.camera, c.width, height, i, j, 0.5f, 0.5f));
  c.view = PinholeView::of(c.camera, c.width, height, window);
  return c;
}

// The camera path where a pixel is finer than its float ray's rounding: fields of view of
// 0.01-0.1 degrees on a plane split by voxel boundaries, 1e3-1e4 from the world origin,
// aimed at the corner where four voxels meet. A float projection of the voxels' outlines
// lost 12-91 of these 6,400 pixels a view (camera_bundles.h, kCameraOutlineEpsilons).
TEST_P(Conformance, NarrowViewsOfABoxFarFromTheOriginMatchBrute) {
  struct View {
    float shift, fov_degrees;
    int height;
  };
  for (const View& v : {View{1e4f, 0.01f, 480}, View{1e3f, 0.01f, 4000}, View{1e4f, 0.1f, 4000}}) {
    const std::vector<GrTriangle> tris =
        squareOverADeepBox(glm::vec3(v.shift, 0.5f * v.shift, 0.0f));
    const Bounds b = boundsOf(tris);
    const UniformGrid grid = buildUniformGrid(tris, b, dims(2, 2, 1));
    glm::vec3 lo, hi;
    grid.voxelBoxOfPe(0, lo, hi);
    const CentreOfView c =
        centreOfView(glm::vec3(hi.x, hi.y, 0.0f), 100.0f, v.fov_degrees, v.height);
    expectAllAgree(tris, b, c.rays, {dims(2, 2, 1)},
                   "shift " + std::to_string(v.shift) + " fov " + std::to_string(v.fov_degrees),
                   &c.view);
  }
}

// A camera 1e5 from a scene 2 across: the rays' hits and voxel crossings round by ~1e-2,
// far more than a margin scaled by the scene's coordinates alone (~5e-5), and the list
// and camera paths lost 1-3 of these 6,400 pixels a view. With the eye in the margin's
// scale (GridSettings::ray_origins) they equal brute force.
TEST_P(Conformance, ACameraFarFromASmallSceneMatchesBrute) {
  const std::vector<GrTriangle> tris = squareOverADeepBox(glm::vec3(0.0f));
  const Bounds b = boundsOf(tris);
  for (float fov_degrees : {0.01f, 0.1f, 1.0f}) {
    const CentreOfView c = centreOfView(b.center(), 1e5f, fov_degrees, 4000);
    GridSettings settings = dims(2, 2, 1);
    settings.ray_origins = primaryRayOrigins(c.camera, c.width, c.height);
    expectAllAgree(tris, b, c.rays, {settings}, "fov " + std::to_string(fov_degrees), &c.view);
  }
}

}  // namespace
}  // namespace gridrt
