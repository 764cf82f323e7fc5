// Where methods fail: grazing rays, tiny and needle triangles, a triangle far larger than
// a voxel, degenerate and NaN input, and the renderer's edge cases (total internal
// reflection, maximum depth, a camera inside glass). Each test names the failure it
// provokes; the float intersectors must agree with brute force bit for bit and with the
// double reference up to the recorded float-vs-double differences.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <random>

#include "brute_intersector.h"
#include "cl_runtime.h"
#include "dda_intersector.h"
#include "default_scene.h"
#include "gltf_loader.h"
#include "gridrt_intersector.h"
#include "kernel_choices.h"
#include "prepared_triangles.h"
#include "reference_intersector.h"
#include "renderer.h"
#include "uniform_grid.h"

namespace gridrt {
namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();

Scene sceneOfTriangles(const std::vector<std::array<glm::vec3, 3>>& tris) {
  Scene s;
  for (const auto& t : tris)
    for (const auto& p : t) s.positions.push_back(p);
  s.material_of.assign(tris.size(), 0);
  s.materials.push_back(Material{});
  return s;
}

class Stability : public ::testing::Test {
 protected:
  void SetUp() override {
    if (listDevices().empty()) GTEST_SKIP() << "no OpenCL device: install pocl-opencl-icd";
    runtime_ = std::make_unique<ClRuntime>("");
  }

  struct Agreement {
    size_t grid_vs_brute = 0;      // bitwise (prim, t) differences: must be 0
    size_t prim_vs_reference = 0;  // different prim or hit/miss against double
    double max_rel_t = 0;          // largest relative t difference against double
  };

  // brute (MT and watertight), gridrt and dda on a 16^3 grid, and the double reference.
  Agreement compare(const Scene& scene, const std::vector<GrRay>& rays, bool watertight) {
    const KernelOptions ko = choice_.options(watertight);
    auto tris = prepareTriangles(scene, ko);
    BruteIntersector brute(*runtime_, tris, ko);
    GridSettings gs;
    gs.automatic = false;
    gs.dims = {16, 16, 16};
    UniformGrid grid = buildUniformGrid(tris, sceneBounds(scene), gs);
    GridRtIntersector gridrt(*runtime_, grid, PeInterrupt::Off, ko);
    DdaIntersector dda(*runtime_, grid, ko);
    ReferenceIntersector ref(scene);
    std::vector<GrHit> want, got, exact;
    brute.intersect(rays, HitMode::Closest, want, nullptr);
    ref.intersect(rays, HitMode::Closest, exact, nullptr);
    Agreement a;
    for (Intersector* x : {static_cast<Intersector*>(&gridrt), static_cast<Intersector*>(&dda)}) {
      x->intersect(rays, HitMode::Closest, got, nullptr);
      for (size_t i = 0; i < rays.size(); ++i)
        a.grid_vs_brute += got[i].prim != want[i].prim ||
                           (want[i].prim >= 0 && std::memcmp(&got[i].t, &want[i].t, 4) != 0);
    }
    for (size_t i = 0; i < rays.size(); ++i) {
      a.prim_vs_reference += want[i].prim != exact[i].prim;
      if (want[i].prim >= 0 && want[i].prim == exact[i].prim)
        a.max_rel_t = std::max(a.max_rel_t, std::fabs(double(want[i].t) - exact[i].t) /
                                                std::max(1e-30, double(exact[i].t)));
    }
    return a;
  }

  void record(const std::string& key, double value) {
    RecordProperty(key, std::to_string(value));
    std::printf("  %-44s %g\n", key.c_str(), value);
  }

  std::unique_ptr<ClRuntime> runtime_;
  // The PE kernels' layout and batch transfer of GridRT here (StabilityKernels names them).
  test::KernelChoice choice_{PeLayout::Auto, BatchTransfer::Map};
};

// The intersection cases, each with both PE layouts and both batch transfers.
class StabilityKernels : public Stability,
                         public ::testing::WithParamInterface<test::KernelChoice> {
 protected:
  void SetUp() override {
    Stability::SetUp();
    choice_ = GetParam();
  }
};

INSTANTIATE_TEST_SUITE_P(Kernels, StabilityKernels, test::kernelChoices(), test::kernelChoiceName);

// Grazing: rays at 1e-1 .. 1e-6 rad to a large triangle, aimed at interior points well
// inside it. The hit is never lost, but t's error grows like 1/sin(angle): recorded.
TEST_P(StabilityKernels, GrazingRaysHitTheSameTriangleAsTheReference) {
  Scene scene =
      sceneOfTriangles({{glm::vec3(-4, 0.5f, -4), glm::vec3(4, 0.5f, -4), glm::vec3(0, 0.5f, 4)},
                        {glm::vec3(-1, 3, -1), glm::vec3(1, 3, -1), glm::vec3(0, 3, 1)}});
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> U(-1.0f, 1.0f);
  std::vector<GrRay> rays;
  for (int e = 1; e <= 6; ++e)
    for (int k = 0; k < 200; ++k) {
      float angle = std::pow(10.0f, -float(e));
      glm::vec3 target(0.8f * U(rng), 0.5f, -1.5f + 0.8f * U(rng));
      float phi = 3.1416f * U(rng);
      glm::vec3 d(std::cos(angle) * std::cos(phi), -std::sin(angle),
                  std::cos(angle) * std::sin(phi));
      glm::vec3 o = target - 2.0f * d;
      rays.push_back(GrRay{o.x, o.y, o.z, 0.0f, d.x, d.y, d.z, kInf});
    }
  for (bool wt : {false, true}) {
    Agreement a = compare(scene, rays, wt);
    std::string name = wt ? "grazing_watertight_" : "grazing_mt_";
    record(name + "prim_vs_reference", double(a.prim_vs_reference));
    record(name + "max_rel_t_error", a.max_rel_t);
    EXPECT_EQ(a.grid_vs_brute, 0u);
    EXPECT_EQ(a.prim_vs_reference, 0u);
  }
}

// Tiny (1e-7) and needle (1 x 1e-7) triangles. Near their own scale they are hit like
// any other; seen from distance 1, o - v0 rounds by ~1e-7, the size of the triangle, and
// float answers differ from double: recorded, not asserted.
TEST_P(StabilityKernels, TinyAndNeedleTrianglesAgreeWithBruteAndNearbyWithTheReference) {
  std::vector<std::array<glm::vec3, 3>> tris;
  for (int i = 0; i < 8; ++i) {
    glm::vec3 c(1e-6f * float(i), 2e-6f, -1e-6f);
    tris.push_back({c, c + glm::vec3(1e-7f, 0, 0), c + glm::vec3(0, 1e-7f, 0)});
  }
  tris.push_back(
      {glm::vec3(0, -1e-5f, 0), glm::vec3(1, -1e-5f, 0), glm::vec3(0.5f, -1e-5f + 1e-7f, 0)});
  Scene scene = sceneOfTriangles(tris);
  std::vector<GrRay> near, far;
  for (size_t t = 0; t < tris.size(); ++t) {
    glm::vec3 c = (tris[t][0] + tris[t][1] + tris[t][2]) / 3.0f;
    for (float dist : {1e-5f, 1.0f}) {
      glm::vec3 o = c + glm::vec3(0.1f, 0.2f, 1.0f) * dist;
      glm::vec3 d = glm::normalize(c - o);
      (dist < 1.0f ? near : far).push_back(GrRay{o.x, o.y, o.z, 0.0f, d.x, d.y, d.z, kInf});
    }
  }
  for (bool wt : {false, true}) {
    Agreement a = compare(scene, near, wt), b = compare(scene, far, wt);
    std::string name = wt ? "tiny_watertight_" : "tiny_mt_";
    record(name + "near_prim_vs_reference", double(a.prim_vs_reference));
    record(name + "far_prim_vs_reference", double(b.prim_vs_reference));
    EXPECT_EQ(a.grid_vs_brute + b.grid_vs_brute, 0u);
    EXPECT_EQ(a.prim_vs_reference, 0u);
  }
}

// One triangle spanning the whole 16^3 grid among small ones: listed in hundreds of
// voxels, its hit must win only in the voxel where it lies (same answers as brute).
TEST_P(StabilityKernels, ATriangleFarLargerThanAVoxelMatchesBrute) {
  std::vector<std::array<glm::vec3, 3>> tris = {
      {glm::vec3(-10, -10, -9), glm::vec3(10, -10, 9), glm::vec3(0, 10, 0)}};
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> U(-10.0f, 10.0f);
  for (int i = 0; i < 300; ++i) {
    glm::vec3 c(U(rng), U(rng), U(rng));
    tris.push_back({c, c + glm::vec3(0.3f, 0, 0), c + glm::vec3(0, 0.3f, 0.1f)});
  }
  Scene scene = sceneOfTriangles(tris);
  std::vector<GrRay> rays;
  for (int i = 0; i < 4000; ++i) {
    glm::vec3 o(U(rng), U(rng), 30.0f), t(U(rng), U(rng), U(rng));
    glm::vec3 d = glm::normalize(t - o);
    rays.push_back(GrRay{o.x, o.y, o.z, 0.0f, d.x, d.y, d.z, kInf});
  }
  for (bool wt : {false, true}) {
    Agreement a = compare(scene, rays, wt);
    record(std::string(wt ? "big_watertight" : "big_mt") + "_prim_vs_reference",
           double(a.prim_vs_reference));
    EXPECT_EQ(a.grid_vs_brute, 0u);
    EXPECT_LE(a.prim_vs_reference, 2u);  // rays through a shared edge or tie: float vs double
  }
}

// Zero-area triangles (a repeated vertex, three equal vertices) and float-collinear
// slivers: the grid builder must not crash, the watertight test never hits a
// repeated-vertex triangle and its grid answers equal brute force. Slivers whose
// rounded vertices are not exactly collinear are real (thin) triangles: counted only.
TEST_P(StabilityKernels, DegenerateTrianglesAreNeverHit) {
  glm::vec3 a(0.3f, 0.2f, 0.1f), b(0.7f, 0.9f, -0.4f);
  std::vector<std::array<glm::vec3, 3>> tris = {
      {a, a, b},
      {a, b, b},
      {a, a, a},
      {a, b, a},
      {a, b, 0.5f * (a + b)},
      {a, 0.25f * a + 0.75f * b, b},
      {glm::vec3(-1, -1, -1), glm::vec3(-0.5f, -1, -1), glm::vec3(-1, -0.5f, -1)}};
  Scene scene = sceneOfTriangles(tris);
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> U(-1.0f, 1.0f), U01(0.0f, 1.0f);
  std::vector<GrRay> rays;
  for (int i = 0; i < 3000; ++i) {
    glm::vec3 target = a + U01(rng) * (b - a);  // on the segment (rounded)
    glm::vec3 o = target + 2.0f * glm::normalize(glm::vec3(U(rng), U(rng), U(rng)));
    glm::vec3 d = glm::normalize(target - o);
    rays.push_back(GrRay{o.x, o.y, o.z, 0.0f, d.x, d.y, d.z, kInf});
  }
  for (bool wt : {false, true}) {
    auto tri_data = prepareTriangles(scene, KernelOptions{wt});
    UniformGrid grid = buildUniformGrid(tri_data, sceneBounds(scene), GridSettings{});
    BruteIntersector brute(*runtime_, tri_data, KernelOptions{wt});
    GridRtIntersector gridrt(*runtime_, grid, PeInterrupt::Off, choice_.options(wt));
    std::vector<GrHit> h, g;
    brute.intersect(rays, HitMode::Closest, h, nullptr);
    gridrt.intersect(rays, HitMode::Closest, g, nullptr);
    size_t repeated = 0, collinear = 0, grid_differs = 0;
    for (size_t i = 0; i < rays.size(); ++i) {
      grid_differs += h[i].prim != g[i].prim;
      repeated += h[i].prim >= 0 && h[i].prim <= 3;
      collinear += h[i].prim == 4 || h[i].prim == 5;
    }
    std::string name = wt ? "degenerate_watertight_" : "degenerate_mt_";
    record(name + "repeated_vertex_hits", double(repeated));
    record(name + "gridrt_differs_from_brute", double(grid_differs));
    record(name + "collinear_hits_of_rays_through_the_segment", double(collinear));
    // Moeller-Trumbore: with e1 == e2, det = e1 . (d x e1) rounds to a tiny non-zero
    // value and u, v, t become garbage: it "hits" repeated-vertex triangles at bogus t,
    // which the grid (hit must lie inside the voxel) then disagrees with. Recorded only.
    // The watertight test gets det exactly 0 (equal projected vertices cancel exactly).
    if (wt) {
      EXPECT_EQ(repeated, 0u);
      EXPECT_EQ(grid_differs, 0u);
    }
  }
}

// NaN/Inf coordinates: the loader drops such triangles and counts them, so the grid
// builder and the kernels never see one (a NaN vertex would make the triangle's box
// NaN and its voxel range undefined).
TEST_P(StabilityKernels, LoaderDropsNanAndInfTrianglesSoTheGridNeverSeesThem) {
  // Three triangles; vertex 4 is NaN, vertex 7 is +Inf. Positions as raw floats, base64.
  float pos[27] = {0, 0, 0, 1, 0, 0, 0, 1,        0, 0, 0, 1, NAN, 0,
                   1, 0, 1, 1, 0, 0, 2, INFINITY, 0, 2, 0, 1, 2};
  std::string bytes(reinterpret_cast<const char*>(pos), sizeof pos), b64;
  const char* tbl = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  for (size_t i = 0; i < bytes.size(); i += 3) {
    uint32_t n = uint8_t(bytes[i]) << 16 | (i + 1 < bytes.size() ? uint8_t(bytes[i + 1]) << 8 : 0) |
                 (i + 2 < bytes.size() ? uint8_t(bytes[i + 2]) : 0);
    b64 += tbl[n >> 18 & 63];
    b64 += tbl[n >> 12 & 63];
    b64 += i + 1 < bytes.size() ? tbl[n >> 6 & 63] : '=';
    b64 += i + 2 < bytes.size() ? tbl[n & 63] : '=';
  }
  std::string json =
      "{\"asset\":{\"version\":\"2.0\"},\"scene\":0,\"scenes\":[{\"nodes\":[0]}],"
      "\"nodes\":[{\"mesh\":0}],\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0}}]}],"
      "\"buffers\":[{\"byteLength\":108,\"uri\":\"data:application/octet-stream;base64," +
      b64 +
      "\"}],\"bufferViews\":[{\"buffer\":0,\"byteLength\":108}],"
      "\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":9,\"type\":\"VEC3\","
      "\"min\":[0,0,0],\"max\":[1,1,2]}]}";
  Scene s = loadGltfFromMemory(reinterpret_cast<const unsigned char*>(json.data()), json.size(), "",
                               "nan.gltf");
  EXPECT_EQ(s.dropped_degenerate, 2u);
  ASSERT_EQ(s.triangleCount(), 1u);
  for (const auto& p : s.positions) EXPECT_TRUE(std::isfinite(p.x + p.y + p.z));
  auto tris = prepareTriangles(s);
  UniformGrid grid = buildUniformGrid(tris, sceneBounds(s), GridSettings{});
  EXPECT_GE(grid.peCount(), 1);
  // NaN and Inf rays: no crash, no hit.
  GridRtIntersector gridrt(*runtime_, grid, PeInterrupt::Off, choice_.options());
  std::vector<GrRay> rays = {{NAN, 0, 1, 0, 0, 0, -1, kInf},
                             {0.2f, 0.2f, 1, 0, NAN, 0, -1, kInf},
                             {0.2f, 0.2f, kInf, 0, 0, 0, -1, kInf}};
  std::vector<GrHit> hits;
  gridrt.intersect(rays, HitMode::Closest, hits, nullptr);
  for (const auto& h : hits) EXPECT_LT(h.prim, 0);
}

// Renderer edge cases: a glass sphere over a lit floor, rendered small with brute force and
// without ambient light, so that what the pixels show is the light's, come through the
// glass (ambient alone would light the floor seen through it).
class GlassRender : public Stability {
 protected:
  Frame render(const Camera& cam, int max_depth) {
    Scene scene;
    Material glass;
    glass.transmission = 1.0f;
    glass.roughness = 0.0f;
    glass.base_color = glm::vec3(1.0f);
    int floor = shapes::addMaterial(scene, Material{});
    int g = shapes::addMaterial(scene, glass);
    shapes::addRect(scene, {0, 0, 0}, {0, 0, 4}, {4, 0, 0}, floor);
    shapes::addSphere(scene, {0, 1, 0}, 0.8f, 32, 16, g);
    Light light;
    light.position = {1, 4, 2};
    light.intensity = 20.0f;
    scene.lights.push_back(light);
    scene.has_lights = true;
    tris_ = prepareTriangles(scene);
    BruteIntersector brute(*runtime_, tris_);
    RenderSettings rs;
    rs.width = 32;
    rs.height = 24;
    rs.max_depth = max_depth;
    rs.ambient = 0.0f;
    Renderer r(scene, cam, brute, rs);
    Frame f;
    r.render(f);
    return f;
  }
  static double mean(const Frame& f, int x0, int x1, int y0, int y1) {
    double s = 0;
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x)
        for (int c = 0; c < 3; ++c) s += f.film.rgb[3 * (y * f.film.width + x) + c];
    return s / (3.0 * (x1 - x0) * (y1 - y0));
  }
  static void expectFiniteNonNegative(const Frame& f) {
    for (float v : f.film.rgb) {
      ASSERT_TRUE(std::isfinite(v));
      ASSERT_GE(v, 0.0f);
    }
  }
  std::vector<GrTriangle> tris_;
};

TEST_F(GlassRender, WithoutBouncesAGlassSphereShowsNoRefraction) {
  Camera cam;
  cam.world = shapes::lookAtWorld({0, 1.2f, 4}, {0, 1, 0});
  Frame f0 = render(cam, 0), f5 = render(cam, 5), f64 = render(cam, 64);
  expectFiniteNonNegative(f0);
  expectFiniteNonNegative(f5);
  expectFiniteNonNegative(f64);  // the deepest allowed: total internal reflection loops end
  // The sphere's centre pixels: glass has no diffuse term, so with max_depth 0 only the
  // highlight could show; with bounces the lit floor shows through it.
  double centre0 = mean(f0, 13, 19, 9, 15), centre5 = mean(f5, 13, 19, 9, 15);
  record("glass_centre_depth0", centre0);
  record("glass_centre_depth5", centre5);
  EXPECT_LT(centre0, 0.05 * centre5);
  EXPECT_GT(centre5, 0.0);
}

TEST_F(GlassRender, ACameraInsideTheGlassSeesTheSceneThroughTheSurface) {
  Camera cam;
  cam.world = shapes::lookAtWorld({0.1f, 1.0f, 0.2f}, {0, 0, 0});  // inside the sphere
  Frame f = render(cam, 5);
  expectFiniteNonNegative(f);
  double m = mean(f, 0, 32, 0, 24);
  record("inside_glass_mean", m);
  EXPECT_GT(m, 0.0);
  // Looking nearly along the surface from inside is total internal reflection: the
  // refracted share is exactly 0 past the critical angle.
  EXPECT_EQ(fresnelDielectric(0.3f, 1.5f), 1.0f);
  EXPECT_LT(fresnelDielectric(0.9f, 1.5f), 1.0f);
}

}  // namespace
}  // namespace gridrt
