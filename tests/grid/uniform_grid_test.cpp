// The uniform grid: every triangle is listed in exactly the voxels whose margin-grown
// closed box it really overlaps (checked against a brute-force all-voxels x all-triangles
// separating-axis test), PE numbering and CSR layout, the auto resolution formula, and the
// degenerate inputs (flat scenes, single points, empty scenes, boundary-plane triangles).
#include "uniform_grid.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include "gltf_loader.h"
#include "grid_dda.h"
#include "parallel_loops.h"
#include "prepared_triangles.h"
#include "scene.h"
#include "test_support.h"
#include "triangle_box_overlap.h"

namespace gridrt {
namespace {

constexpr double kPi = 3.14159265358979323846;

Scene sceneOf(const std::vector<glm::vec3>& positions) {
  Scene s;
  s.positions = positions;
  return s;
}

// A soup of `count` random triangles: centres in [lo, hi], sizes log-uniform over
// [1e-3, 3], so some are tiny and some span many voxels.
std::vector<glm::vec3> randomSoup(uint32_t seed, int count, glm::vec3 lo, glm::vec3 hi) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  std::normal_distribution<float> gauss(0.0f, 1.0f);
  std::vector<glm::vec3> p;
  for (int t = 0; t < count; ++t) {
    glm::vec3 c(lo.x + (hi.x - lo.x) * unit(rng), lo.y + (hi.y - lo.y) * unit(rng),
                lo.z + (hi.z - lo.z) * unit(rng));
    float size = std::pow(10.0f, -3.0f + 3.5f * unit(rng));
    for (int k = 0; k < 3; ++k)
      p.push_back(c + size * glm::vec3(gauss(rng), gauss(rng), gauss(rng)));
  }
  return p;
}

std::vector<glm::vec3> uvSphere(glm::vec3 centre, float radius, int rings, int segments) {
  auto at = [&](int i, int j) {
    double th = kPi * i / rings, ph = 2.0 * kPi * j / segments;
    return centre + radius * glm::vec3(float(std::sin(th) * std::cos(ph)),
                                       float(std::sin(th) * std::sin(ph)), float(std::cos(th)));
  };
  std::vector<glm::vec3> p;
  for (int i = 0; i < rings; ++i)
    for (int j = 0; j < segments; ++j) {
      glm::vec3 a = at(i, j), b = at(i + 1, j), c = at(i + 1, j + 1), d = at(i, j + 1);
      if (i != rings - 1) p.insert(p.end(), {a, b, c});
      if (i != 0) p.insert(p.end(), {a, c, d});
    }
  return p;
}

GridSettings fixedDims(int nx, int ny, int nz, double margin_rel = kGridMarginRel) {
  GridSettings s;
  s.automatic = false;
  s.dims = {nx, ny, nz};
  s.margin_rel = margin_rel;
  return s;
}

GridSettings autoDims() { return GridSettings{}; }

// Triangle vertices exactly as the grid (and the intersectors) define them.
void verticesOf(const GrTriangle& t, glm::dvec3 v[3]) { triangleVertices(t, v); }

// The closed box of voxel (x, y, z) grown by the grid's margin.
void grownVoxelBox(const UniformGrid& g, int x, int y, int z, glm::dvec3& lo, glm::dvec3& hi) {
  glm::dvec3 gmin(g.info.minx, g.info.miny, g.info.minz);
  glm::dvec3 cell(g.info.cellx, g.info.celly, g.info.cellz);
  lo = gmin + glm::dvec3(x, y, z) * cell - g.margin;
  hi = gmin + glm::dvec3(x + 1, y + 1, z + 1) * cell + g.margin;
}

// The global triangle indices the grid lists in voxel v (empty for an empty voxel).
std::vector<int> listedIn(const UniformGrid& g, size_t v) {
  std::vector<int> out;
  int pe = g.pe_of_voxel[v];
  if (pe < 0) return out;
  for (int i = g.pe_tri_begin[pe]; i < g.pe_tri_begin[pe + 1]; ++i)
    out.push_back(g.pe_triangles[i].prim);
  return out;
}

// Structural invariants: dimensions, PE <-> voxel maps, CSR, per-PE order, triangle data.
void expectWellFormed(const UniformGrid& g, const std::vector<GrTriangle>& tris) {
  const GrGridInfo& in = g.info;
  ASSERT_GE(in.nx, 1);
  ASSERT_GE(in.ny, 1);
  ASSERT_GE(in.nz, 1);
  ASSERT_LE(in.nx, kMaxGridResolution);
  ASSERT_LE(in.ny, kMaxGridResolution);
  ASSERT_LE(in.nz, kMaxGridResolution);
  ASSERT_LE((long long)in.nx * in.ny * in.nz, kMaxGridVoxels);
  ASSERT_EQ(g.voxelCount(), size_t(in.nx) * in.ny * in.nz);
  for (float c : {in.cellx, in.celly, in.cellz}) {
    EXPECT_TRUE(std::isfinite(c));
    EXPECT_GT(c, 0.0f);
  }
  for (float m : {in.minx, in.miny, in.minz}) EXPECT_TRUE(std::isfinite(m));
  EXPECT_TRUE(std::isfinite(g.margin));
  EXPECT_GT(g.margin, 0.0);
  EXPECT_EQ(g.triangle_count, tris.size());
  EXPECT_EQ(in.pe_count, g.peCount());

  // PE <-> voxel maps are inverse, PEs numbered in increasing voxel order.
  const int pes = g.peCount();
  for (int pe = 0; pe < pes; ++pe) {
    int v = g.voxel_of_pe[pe];
    ASSERT_GE(v, 0);
    ASSERT_LT(size_t(v), g.voxelCount());
    ASSERT_EQ(g.pe_of_voxel[v], pe);
    if (pe > 0) {
      ASSERT_LT(g.voxel_of_pe[pe - 1], v);
    }
  }
  int mapped = 0;
  for (size_t v = 0; v < g.voxelCount(); ++v) {
    int pe = g.pe_of_voxel[v];
    ASSERT_GE(pe, -1);
    if (pe < 0) continue;
    ++mapped;
    ASSERT_LT(pe, pes);
    ASSERT_EQ(size_t(g.voxel_of_pe[pe]), v);
  }
  ASSERT_EQ(mapped, pes);

  // CSR: pes + 1 offsets from 0 to the triangle array's size, every PE non-empty.
  ASSERT_EQ(g.pe_tri_begin.size(), size_t(pes) + 1);
  ASSERT_EQ(g.pe_tri_begin[0], 0);
  for (int pe = 0; pe < pes; ++pe) ASSERT_GT(g.triangleCountOfPe(pe), 0) << "PE " << pe;
  ASSERT_EQ(size_t(g.pe_tri_begin[pes]), g.pe_triangles.size());

  // Per PE: strictly increasing global index, triangle data bit-identical to the input.
  for (int pe = 0; pe < pes; ++pe)
    for (int i = g.pe_tri_begin[pe]; i < g.pe_tri_begin[pe + 1]; ++i) {
      const GrTriangle& t = g.pe_triangles[i];
      ASSERT_GE(t.prim, 0);
      ASSERT_LT(size_t(t.prim), tris.size());
      if (i > g.pe_tri_begin[pe]) {
        ASSERT_LT(g.pe_triangles[i - 1].prim, t.prim) << "PE " << pe;
      }
      ASSERT_EQ(std::memcmp(&t, &tris[t.prim], sizeof(GrTriangle)), 0) << "PE " << pe;
    }
}

// Whether the triangle a, b, c meets the closed box [lo, hi], decided independently of the
// builder's separating-axis test: the triangle clipped by the box's six planes in turn
// (Sutherland-Hodgman, in double; a clipped point takes the plane's coordinate exactly)
// leaves something.
bool clippedTriangleIsLeft(const glm::dvec3& lo, const glm::dvec3& hi, const glm::dvec3& a,
                           const glm::dvec3& b, const glm::dvec3& c) {
  std::vector<glm::dvec3> polygon{a, b, c}, next;
  for (int axis = 0; axis < 3; ++axis)
    for (int side = 0; side < 2; ++side) {
      const double plane = side == 0 ? lo[axis] : hi[axis];
      auto inside = [&](const glm::dvec3& p) {
        return side == 0 ? p[axis] >= plane : p[axis] <= plane;
      };
      next.clear();
      for (size_t k = 0; k < polygon.size(); ++k) {
        const glm::dvec3 &p = polygon[k], &q = polygon[(k + 1) % polygon.size()];
        if (inside(p)) next.push_back(p);
        if (inside(p) != inside(q)) {
          const double s = (plane - p[axis]) / (q[axis] - p[axis]);
          glm::dvec3 x = p + s * (q - p);
          x[axis] = plane;
          next.push_back(x);
        }
      }
      polygon.swap(next);
      if (polygon.empty()) return false;
    }
  return true;
}

// Brute force: every voxel against every triangle, by clipping; the grid must list exactly
// those.
void expectExactLists(const UniformGrid& g, const std::vector<GrTriangle>& tris) {
  std::vector<std::array<glm::dvec3, 3>> verts(tris.size());
  for (size_t t = 0; t < tris.size(); ++t) verticesOf(tris[t], verts[t].data());
  std::vector<int> times_listed(tris.size(), 0);
  int bad = 0;
  for (int z = 0; z < g.info.nz; ++z)
    for (int y = 0; y < g.info.ny; ++y)
      for (int x = 0; x < g.info.nx; ++x) {
        glm::dvec3 lo, hi;
        grownVoxelBox(g, x, y, z, lo, hi);
        std::vector<int> want;
        for (size_t t = 0; t < tris.size(); ++t)
          if (clippedTriangleIsLeft(lo, hi, verts[t][0], verts[t][1], verts[t][2]))
            want.push_back(int(t));
        size_t v = size_t(x) + size_t(g.info.nx) * (y + size_t(g.info.ny) * z);
        std::vector<int> got = listedIn(g, v);
        for (int t : got) ++times_listed[t];
        if (got != want && bad++ < 5)
          ADD_FAILURE() << "voxel (" << x << "," << y << "," << z << "): grid lists " << got.size()
                        << " triangles, brute force finds " << want.size();
      }
  EXPECT_EQ(bad, 0) << "voxels whose list differs from brute force";
  // The grid box covers the scene: every triangle is somewhere.
  for (size_t t = 0; t < tris.size(); ++t)
    EXPECT_GT(times_listed[t], 0) << "triangle " << t << " is in no voxel";
}

void expectGridCorrect(const std::vector<glm::vec3>& positions, const GridSettings& settings,
                       const std::string& label) {
  SCOPED_TRACE(label);
  Scene scene = sceneOf(positions);
  std::vector<GrTriangle> tris = prepareTriangles(scene);
  UniformGrid g = buildUniformGrid(tris, sceneBounds(scene), settings);
  SCOPED_TRACE(std::to_string(g.info.nx) + "x" + std::to_string(g.info.ny) + "x" +
               std::to_string(g.info.nz));
  if (!settings.automatic) {
    EXPECT_EQ(g.info.nx, settings.dims.x);
    EXPECT_EQ(g.info.ny, settings.dims.y);
    EXPECT_EQ(g.info.nz, settings.dims.z);
  }
  expectWellFormed(g, tris);
  expectExactLists(g, tris);
}

const std::vector<GridSettings>& allResolutions() {
  static const std::vector<GridSettings> r = {fixedDims(1, 1, 1), fixedDims(3, 3, 3),
                                              fixedDims(7, 5, 3), autoDims()};
  return r;
}

TEST(UniformGrid, EveryTriangleIsInEveryVoxelItOverlapsAndNoOtherOnRandomSoups) {
  for (uint32_t seed : {1u, 2u, 3u}) {
    auto soup = randomSoup(seed, 250, {-3.0f, -1.0f, 0.0f}, {5.0f, 1.0f, 2.0f});
    for (const auto& s : allResolutions())
      expectGridCorrect(soup, s, "soup " + std::to_string(seed));
  }
}

TEST(UniformGrid, EveryTriangleIsInEveryVoxelItOverlapsAndNoOtherOnASphere) {
  auto sphere = uvSphere({0.25f, -0.5f, 1.0f}, 2.0f, 16, 32);
  for (const auto& s : allResolutions()) expectGridCorrect(sphere, s, "sphere");
}

TEST(UniformGrid, EveryTriangleIsInEveryVoxelItOverlapsAndNoOtherOnTheBunny) {
  std::string path = test::modelScene("bunny_res4.glb");
  ASSERT_TRUE(test::fileExists(path)) << path;
  Scene scene = loadGltfFile(path);
  ASSERT_GT(scene.triangleCount(), 100u);
  for (const auto& s : allResolutions()) expectGridCorrect(scene.positions, s, "bunny_res4");
}

TEST(UniformGrid, ListsDoNotDependOnTheThreadCount) {
  Scene scene = sceneOf(randomSoup(7, 400, {0, 0, 0}, {4, 4, 4}));
  auto tris = prepareTriangles(scene);
  auto buildWith = [&](int threads) {
    const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
    return buildUniformGrid(tris, sceneBounds(scene), fixedDims(6, 5, 4));
  };
  UniformGrid one = buildWith(1);
  UniformGrid seven = buildWith(7);
  expectWellFormed(seven, tris);
  EXPECT_EQ(one.pe_of_voxel, seven.pe_of_voxel);
  EXPECT_EQ(one.voxel_of_pe, seven.voxel_of_pe);
  EXPECT_EQ(one.pe_tri_begin, seven.pe_tri_begin);
  ASSERT_EQ(one.pe_triangles.size(), seven.pe_triangles.size());
  for (size_t i = 0; i < one.pe_triangles.size(); ++i)
    ASSERT_EQ(one.pe_triangles[i].prim, seven.pe_triangles[i].prim) << i;
}

// AxisCells::range against its definition by a scan of every cell: first is the lowest
// cell whose grown upper face reaches lo, last the highest whose grown lower face is at or
// below hi (both widened by the slack), on uneven planes and on values at, just beside and
// far beyond the planes, where a shortcut would pick a neighbouring cell.
TEST(AxisCells, RangeEqualsAScanOfEveryCell) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int trial = 0; trial < 200; ++trial) {
    const int cells = 1 + int(unit(rng) * 40);
    std::vector<float> planes(size_t(cells) + 1);
    planes[0] = float(-5.0 + 10.0 * unit(rng));
    for (int k = 1; k <= cells; ++k)  // about even, some cells twice or half the mean
      planes[k] = planes[k - 1] + float(0.5 + 1.5 * unit(rng));
    const double m = trial % 3 == 0 ? 0.0 : 1e-3 * unit(rng);
    const AxisCells axis(planes, m);
    const double slack = 1e-9 * ((double(planes[cells]) - planes[0]) / cells);
    // A value whose reach (x -/+ m -/+ slack, as range rounds it) lands exactly on p.
    auto reachingExactly = [&](double p, bool as_lo) {
      double x = as_lo ? p + m + slack : p - m - slack;
      for (int step = 0; step < 64; ++step) {
        const double reach = as_lo ? x - m - slack : x + m + slack;
        if (reach == p) return x;
        x = std::nextafter(x, reach < p ? INFINITY : -INFINITY);
      }
      return x;  // none found: an ordinary value near p
    };
    for (int q = 0; q < 200; ++q) {
      auto value = [&](bool as_lo) {
        const double pick = unit(rng);
        const double p = planes[size_t(unit(rng) * (cells + 1)) % (cells + 1)];
        if (pick < 0.15) return reachingExactly(p, as_lo);                 // the reach on a plane
        if (pick < 0.3) return p;                                          // on a plane
        if (pick < 0.6) return p + (unit(rng) - 0.5) * 4.0 * (m + slack);  // beside one
        return double(planes[0]) - 3.0 + (double(planes[cells]) - planes[0] + 6.0) * unit(rng);
      };
      double lo = value(true), hi = value(false);
      if (lo > hi) std::swap(lo, hi);
      int want_first = cells - 1, want_last = 0;
      for (int i = cells - 1; i >= 0; --i)
        if (double(planes[i + 1]) >= lo - m - slack) want_first = i;
      for (int i = 0; i < cells; ++i)
        if (double(planes[i]) <= hi + m + slack) want_last = i;
      int first = -1, last = -1;
      axis.range(lo, hi, first, last);
      ASSERT_EQ(first, want_first) << "trial " << trial << " lo " << lo << " hi " << hi;
      ASSERT_EQ(last, want_last) << "trial " << trial << " lo " << lo << " hi " << hi;
    }
  }
}

TEST(UniformGrid, VoxelCoordsInvertsTheLinearIndex) {
  Scene scene = sceneOf(randomSoup(4, 20, {0, 0, 0}, {1, 1, 1}));
  UniformGrid g = buildUniformGrid(prepareTriangles(scene), sceneBounds(scene), fixedDims(7, 5, 3));
  for (int z = 0; z < 3; ++z)
    for (int y = 0; y < 5; ++y)
      for (int x = 0; x < 7; ++x)
        EXPECT_EQ(g.voxelCoords(x + 7 * (y + 5 * z)), glm::ivec3(x, y, z));
}

// Exactness: a long thin triangle along the diagonal of a 10x10x1 grid has a bounding box
// covering all 100 voxels but overlaps only the voxels along the diagonal.
TEST(UniformGrid, ThinDiagonalTriangleIsListedOnlyInTheVoxelsItOverlapsNotItsBoundingBox) {
  Scene scene = sceneOf({{0.3f, 0.5f, 0.5f}, {9.3f, 9.5f, 0.5f}, {9.32f, 9.47f, 0.5f}});
  auto tris = prepareTriangles(scene);
  Bounds box;
  box.grow({0, 0, 0});
  box.grow({10, 10, 1});
  UniformGrid g = buildUniformGrid(tris, box, fixedDims(10, 10, 1));
  expectWellFormed(g, tris);
  expectExactLists(g, tris);
  // Its bounding box spans voxels x 0..9, y 0..9: 100 voxels.
  EXPECT_LT(g.peCount(), 100 / 4);
  EXPECT_GE(g.peCount(), 10);
  for (int pe = 0; pe < g.peCount(); ++pe) {
    glm::ivec3 c = g.voxelCoords(g.voxel_of_pe[pe]);
    EXPECT_LE(std::abs(c.x - c.y), 1) << "off-diagonal voxel (" << c.x << "," << c.y << ")";
  }
  EXPECT_EQ(g.pe_of_voxel[9 + 10 * 0], -1);
  EXPECT_EQ(g.pe_of_voxel[0 + 10 * 9], -1);
  EXPECT_EQ(g.pe_of_voxel[5 + 10 * 2], -1);
  for (int k = 0; k < 10; ++k) EXPECT_GE(g.pe_of_voxel[k + 10 * k], 0) << "diagonal voxel " << k;
}

TEST(UniformGrid, SmallTriangleInACornerVoxelIsListedOnlyThere) {
  Scene scene = sceneOf({{0.2f, 0.3f, 0.4f}, {0.6f, 0.3f, 0.4f}, {0.4f, 0.7f, 0.6f}});
  auto tris = prepareTriangles(scene);
  Bounds box;
  box.grow({0, 0, 0});
  box.grow({3, 3, 3});
  UniformGrid g = buildUniformGrid(tris, box, fixedDims(3, 3, 3));
  expectWellFormed(g, tris);
  ASSERT_EQ(g.peCount(), 1);
  EXPECT_EQ(g.voxel_of_pe[0], 0);
  EXPECT_EQ(listedIn(g, 0), std::vector<int>{0});
}

TEST(UniformGrid, AutoResolutionFollowsCubeRootOfDensityTimesCountOverVolume) {
  Bounds b;
  b.grow({-1, 0, 2});
  b.grow({3, 2, 3});  // extents 4 x 2 x 1, V = 8
  // cbrt(4 * 1000 / 8) = 7.937: 31.75, 15.87, 7.94
  EXPECT_EQ(autoGridResolution(b, 1000, 4.0f), glm::ivec3(32, 16, 8));
  // cbrt(1 * 1000 / 8) = 5: 20, 10, 5
  EXPECT_EQ(autoGridResolution(b, 1000, 1.0f), glm::ivec3(20, 10, 5));
  // cbrt(4 * 10 / 8) = 1.71: 6.84, 3.42, 1.71
  EXPECT_EQ(autoGridResolution(b, 10, 4.0f), glm::ivec3(7, 3, 2));
  Bounds cube;
  cube.grow({0, 0, 0});
  cube.grow({2, 2, 2});
  // cbrt(4 * 54 / 8) = 3: 6 per axis
  EXPECT_EQ(autoGridResolution(cube, 54, 4.0f), glm::ivec3(6, 6, 6));
  // A single triangle in a cube: cbrt(4 / 8) = 0.79: 1.59 -> 2
  EXPECT_EQ(autoGridResolution(cube, 1, 4.0f), glm::ivec3(2, 2, 2));
  // A long thin box never drops an axis below 1.
  Bounds rod;
  rod.grow({0, 0, 0});
  rod.grow({100, 1, 1});
  glm::ivec3 r = autoGridResolution(rod, 10, 4.0f);
  EXPECT_GE(r.y, 1);
  EXPECT_GE(r.z, 1);
  EXPECT_GT(r.x, r.y);
  // The builder uses exactly this resolution.
  Scene scene = sceneOf(randomSoup(9, 300, {-1, 0, 2}, {3, 2, 3}));
  auto tris = prepareTriangles(scene);
  Bounds sb = sceneBounds(scene);
  for (float density : {1.0f, 4.0f, 9.0f}) {
    GridSettings s;
    s.density = density;
    UniformGrid g = buildUniformGrid(tris, sb, s);
    EXPECT_EQ(glm::ivec3(g.info.nx, g.info.ny, g.info.nz),
              autoGridResolution(sb, tris.size(), density));
  }
}

TEST(UniformGrid, AutoResolutionStaysWithinTheVoxelLimits) {
  Bounds cube;
  cube.grow({0, 0, 0});
  cube.grow({1, 1, 1});
  for (size_t n : {size_t(1) << 20, size_t(1) << 30, size_t(1) << 40}) {
    glm::ivec3 r = autoGridResolution(cube, n, 100.0f);
    EXPECT_LE(r.x, kMaxGridResolution);
    EXPECT_LE(r.y, kMaxGridResolution);
    EXPECT_LE(r.z, kMaxGridResolution);
    EXPECT_GE(glm::min(r.x, glm::min(r.y, r.z)), 1);
    EXPECT_LE((long long)r.x * r.y * r.z, kMaxGridVoxels);
  }
  Bounds slab;
  slab.grow({0, 0, 0});
  slab.grow({1000, 1000, 1});
  glm::ivec3 r = autoGridResolution(slab, size_t(1) << 32, 4.0f);
  EXPECT_LE((long long)r.x * r.y * r.z, kMaxGridVoxels);
  EXPECT_LE(r.x, kMaxGridResolution);
  EXPECT_GE(r.z, 1);
  // Manual dimensions are clamped to the limits too.
  Scene scene = sceneOf({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
  UniformGrid g = buildUniformGrid(prepareTriangles(scene), sceneBounds(scene),
                                   fixedDims(0, -3, kMaxGridResolution + 100));
  EXPECT_EQ(glm::ivec3(g.info.nx, g.info.ny, g.info.nz), glm::ivec3(1, 1, kMaxGridResolution));
}

TEST(UniformGrid, FlatSceneGivesAValidGridWithNonZeroCells) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  std::vector<glm::vec3> p;
  for (int i = 0; i < 3 * 100; ++i) p.push_back({u(rng), u(rng), 0.0f});
  expectGridCorrect(p, autoDims(), "flat z=0");
  Scene scene = sceneOf(p);
  UniformGrid g = buildUniformGrid(prepareTriangles(scene), sceneBounds(scene), autoDims());
  EXPECT_GE(g.info.nz, 1);
  EXPECT_GT(g.info.nx, 1);
  EXPECT_GT(g.info.ny, 1);
  EXPECT_GT(g.info.cellz, 0.0f);
  EXPECT_TRUE(std::isfinite(g.info.cellz));
  // The grid's z slab contains the plane.
  EXPECT_LT(g.info.minz, 0.0f);
  EXPECT_GT(g.info.minz + g.info.nz * g.info.cellz, 0.0f);
  for (const auto& s : allResolutions()) expectGridCorrect(p, s, "flat z=0");
}

TEST(UniformGrid, SingleTriangleGivesAValidGrid) {
  std::vector<glm::vec3> p = {{1.0f, 2.0f, 3.0f}, {1.5f, 2.1f, 3.2f}, {0.9f, 2.7f, 3.1f}};
  for (const auto& s : allResolutions()) expectGridCorrect(p, s, "single triangle");
  Scene scene = sceneOf(p);
  UniformGrid g = buildUniformGrid(prepareTriangles(scene), sceneBounds(scene), autoDims());
  EXPECT_GE(g.peCount(), 1);
}

TEST(UniformGrid, DegenerateTriangleIsListedInTheVoxelContainingItsPoint) {
  // Among ordinary triangles.
  std::vector<glm::vec3> p = randomSoup(5, 30, {0, 0, 0}, {1, 1, 1});
  const glm::vec3 point(0.37f, 0.61f, 0.29f);
  p.insert(p.end(), {point, point, point});
  const int degenerate = int(p.size() / 3 - 1);
  for (const auto& s : allResolutions()) {
    expectGridCorrect(p, s, "degenerate among others");
    Scene scene = sceneOf(p);
    UniformGrid g = buildUniformGrid(prepareTriangles(scene), sceneBounds(scene), s);
    glm::ivec3 c(int(std::floor((point.x - g.info.minx) / g.info.cellx)),
                 int(std::floor((point.y - g.info.miny) / g.info.celly)),
                 int(std::floor((point.z - g.info.minz) / g.info.cellz)));
    auto list = listedIn(g, c.x + g.info.nx * (c.y + g.info.ny * c.z));
    EXPECT_NE(std::find(list.begin(), list.end(), degenerate), list.end());
  }
  // Alone: the scene collapses to one point (also at the origin, where the margin has
  // no scale to be relative to).
  for (glm::vec3 q : {glm::vec3(1000.0f, -5.0f, 3.0f), glm::vec3(0.0f)}) {
    Scene scene = sceneOf({q, q, q});
    auto tris = prepareTriangles(scene);
    for (const auto& s : allResolutions()) {
      UniformGrid g = buildUniformGrid(tris, sceneBounds(scene), s);
      SCOPED_TRACE("point (" + std::to_string(q.x) + "," + std::to_string(q.y) + "," +
                   std::to_string(q.z) + ") grid " + std::to_string(g.info.nx) + "x" +
                   std::to_string(g.info.ny) + "x" + std::to_string(g.info.nz));
      expectWellFormed(g, tris);
      expectExactLists(g, tris);
      if (s.automatic) {
        EXPECT_EQ(g.voxelCount(), 1u);
      }
    }
  }
}

TEST(UniformGrid, EmptyTriangleListGivesNoPEs) {
  for (const auto& s : allResolutions()) {
    UniformGrid g = buildUniformGrid({}, Bounds{}, s);
    expectWellFormed(g, {});
    EXPECT_EQ(g.peCount(), 0);
    EXPECT_EQ(g.info.pe_count, 0);
    EXPECT_TRUE(g.pe_triangles.empty());
    EXPECT_EQ(g.pe_tri_begin, std::vector<int>{0});
    for (int v : g.pe_of_voxel) EXPECT_EQ(v, -1);
  }
}

// Two voxels side by side over [0,2] x [0,1] x [0,1]: the boundary plane is x = 1.
UniformGrid twoVoxels(const std::vector<glm::vec3>& p, double margin_rel,
                      std::vector<GrTriangle>& tris) {
  Scene scene = sceneOf(p);
  tris = prepareTriangles(scene);
  Bounds box;
  box.grow({0, 0, 0});
  box.grow({2, 1, 1});
  return buildUniformGrid(tris, box, fixedDims(2, 1, 1, margin_rel));
}

TEST(UniformGrid, TriangleInAVoxelBoundaryPlaneIsListedInBothVoxelsWithoutMargin) {
  std::vector<GrTriangle> tris;
  UniformGrid g =
      twoVoxels({{1.0f, 0.2f, 0.2f}, {1.0f, 0.8f, 0.2f}, {1.0f, 0.5f, 0.8f}}, 0.0, tris);
  ASSERT_EQ(double(g.info.minx) + double(g.info.cellx), 1.0);
  expectWellFormed(g, tris);
  EXPECT_EQ(listedIn(g, 0), std::vector<int>{0});
  EXPECT_EQ(listedIn(g, 1), std::vector<int>{0});
  // A triangle touching the plane with one vertex only is in both too (closed sets) ...
  g = twoVoxels({{1.0f, 0.2f, 0.2f}, {1.5f, 0.8f, 0.2f}, {1.5f, 0.5f, 0.8f}}, 0.0, tris);
  EXPECT_EQ(listedIn(g, 0), std::vector<int>{0});
  EXPECT_EQ(listedIn(g, 1), std::vector<int>{0});
  // ... but one just past the plane is not, without a margin.
  g = twoVoxels({{1.001f, 0.2f, 0.2f}, {1.5f, 0.8f, 0.2f}, {1.5f, 0.5f, 0.8f}}, 0.0, tris);
  EXPECT_TRUE(listedIn(g, 0).empty());
  EXPECT_EQ(listedIn(g, 1), std::vector<int>{0});
}

// AxisCells::range widens a triangle's reach by a billionth of a cell, so it may name a
// cell the triangle misses by less than that; the binning decides exactly even where no
// separating-axis test runs (a triangle crossing cells along one axis only,
// triangle_cells.h). Near a plane at 0, floats lie that close to it.
TEST(UniformGrid, TriangleJustPastAPlaneWithinTheRangesSlackIsNotListedBeforeIt) {
  const float x0 = 1e-10f;  // past the plane at 0 by a tenth of the slack (1e-9 of a cell)
  const std::vector<glm::vec3> positions = {
      {x0, 0.2f, 0.2f}, {0.8f, 0.8f, 0.2f}, {0.8f, 0.5f, 0.8f}};
  const std::vector<GrTriangle> tris = prepareTriangles(sceneOf(positions));
  Bounds box;
  box.grow({-1, 0, 0});
  box.grow({1, 1, 1});
  const UniformGrid g = buildUniformGrid(tris, box, fixedDims(2, 1, 1, 0.0));
  ASSERT_EQ(gr_grid_plane(g.info.minx, g.info.cellx, 1), 0.0f);
  EXPECT_TRUE(listedIn(g, 0).empty());
  EXPECT_EQ(listedIn(g, 1), std::vector<int>{0});
  expectExactLists(g, tris);
}

TEST(UniformGrid, TriangleWithinTheMarginOfANeighbouringVoxelIsListedThere) {
  std::vector<GrTriangle> tris;
  UniformGrid g =
      twoVoxels({{1.5f, 0.5f, 0.5f}, {1.6f, 0.5f, 0.5f}, {1.5f, 0.6f, 0.5f}}, kGridMarginRel, tris);
  const double m = g.margin;
  // margin_rel * the box's diagonal = 1e-5 * sqrt(6): the longest way through the grid
  EXPECT_NEAR(m, kGridMarginRel * std::sqrt(6.0), 1e-12);
  const double plane = double(g.info.minx) + double(g.info.cellx);
  ASSERT_NEAR(plane, 1.0, 1e-6);
  auto triangleAt = [&](double x) {
    float fx = float(x);
    return std::vector<glm::vec3>{
        {fx, 0.2f, 0.2f}, {fx + 0.3f, 0.8f, 0.2f}, {fx + 0.3f, 0.5f, 0.8f}};
  };
  // Nearest vertex half a margin inside voxel 1: listed in voxel 0 too.
  g = twoVoxels(triangleAt(plane + 0.5 * m), kGridMarginRel, tris);
  EXPECT_EQ(listedIn(g, 0), std::vector<int>{0});
  EXPECT_EQ(listedIn(g, 1), std::vector<int>{0});
  expectExactLists(g, tris);
  // Two margins inside voxel 1: only there.
  g = twoVoxels(triangleAt(plane + 2.0 * m), kGridMarginRel, tris);
  EXPECT_TRUE(listedIn(g, 0).empty());
  EXPECT_EQ(listedIn(g, 1), std::vector<int>{0});
  // The same triangle half a margin inside, without a margin: only in voxel 1.
  g = twoVoxels(triangleAt(1.0 + 0.5 * m), 0.0, tris);
  EXPECT_TRUE(listedIn(g, 0).empty());
  EXPECT_EQ(listedIn(g, 1), std::vector<int>{0});
}

}  // namespace
}  // namespace gridrt
