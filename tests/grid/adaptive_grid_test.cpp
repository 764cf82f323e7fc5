// The adaptive structure (host/grid/adaptive_grid.h) and its traversal lists
// (host/gridrt/lists/adaptive_lists.h) against brute force: every leaf holds exactly the
// triangles that overlap its box grown by the grid's margin, leaves never overlap, and a
// ray's list puts every point of the ray that lies inside a leaf in an entry of that leaf.
#include "adaptive_grid.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>

#include "adaptive_lists.h"
#include "gltf_loader.h"
#include "prepared_triangles.h"
#include "test_support.h"
#include "triangle_box_overlap.h"
#include "uneven_scenes.h"

namespace gridrt {
namespace {

struct Built {
  std::vector<GrTriangle> triangles;
  UniformGrid grid;
};

// The bunny_res4 on a floor `scale` times its size, with leaves of at most `leaf`
// triangles (small ones reach the deeper levels).
Built build(float scale, int leaf) {
  static const Scene bunny = loadGltfFile(test::modelScene("bunny_res4.glb"));
  Built b;
  const Scene scene = floorScene(bunny, scale);
  b.triangles = prepareTriangles(scene);
  GridSettings s;
  s.structure = GridStructure::Adaptive;
  s.max_leaf_triangles = leaf;
  b.grid = buildAdaptiveGrid(b.triangles, sceneBounds(scene), s);
  return b;
}

void boxOf(const UniformGrid& g, int pe, glm::dvec3& lo, glm::dvec3& hi) {
  glm::vec3 l, h;
  g.voxelBoxOfPe(pe, l, h);
  lo = glm::dvec3(l);
  hi = glm::dvec3(h);
}

bool inside(const glm::dvec3& p, const glm::dvec3& lo, const glm::dvec3& hi, double grow) {
  for (int a = 0; a < 3; ++a)
    if (p[a] < lo[a] - grow || p[a] > hi[a] + grow) return false;
  return true;
}

// --grid auto (GridStructure::WhereNeeded) refines only where a voxel of the uniform grid
// is fuller than the leaf limit: bunny_res4 alone keeps its uniform grid, voxel for voxel;
// on a floor 100 times its size the model shares a voxel, which is refined.
TEST(AdaptiveGrid, WhereNeededRefinesOnlyAUniformGridWithAFullVoxel) {
  const Scene bunny = loadGltfFile(test::modelScene("bunny_res4.glb"));
  GridSettings where_needed;
  where_needed.structure = GridStructure::WhereNeeded;
  const std::vector<GrTriangle> alone = prepareTriangles(bunny);
  const UniformGrid kept = buildGrid(alone, sceneBounds(bunny), where_needed);
  const UniformGrid uniform = buildGrid(alone, sceneBounds(bunny), GridSettings{});
  EXPECT_TRUE(kept.adaptive.empty());
  EXPECT_EQ(kept.pe_of_voxel, uniform.pe_of_voxel);
  EXPECT_EQ(kept.pe_triangles.size(), uniform.pe_triangles.size());
  int fullest = 0;
  for (int pe = 0; pe < uniform.peCount(); ++pe)
    fullest = std::max(fullest, uniform.triangleCountOfPe(pe));
  ASSERT_LE(fullest, where_needed.max_leaf_triangles);

  const Scene floor = floorScene(bunny, 100.0f);
  const std::vector<GrTriangle> on_floor = prepareTriangles(floor);
  const UniformGrid refined = buildGrid(on_floor, sceneBounds(floor), where_needed);
  EXPECT_FALSE(refined.adaptive.empty());
  EXPECT_GE(refined.adaptive.depth, 1);
  // Just above the fullest voxel the bunny alone is still left as it is; just below, not.
  where_needed.max_leaf_triangles = fullest - 1;
  EXPECT_FALSE(buildGrid(alone, sceneBounds(bunny), where_needed).adaptive.empty());
}

TEST(AdaptiveGrid, LeavesHoldExactlyTheTrianglesOverlappingTheirGrownBoxes) {
  for (int leaf : {256, 16}) {
    const Built b = build(100.0f, leaf);
    const UniformGrid& g = b.grid;
    ASSERT_FALSE(g.adaptive.empty());
    if (leaf == 16) {
      EXPECT_GE(g.adaptive.depth, 2);
    }
    size_t wrong = 0;
    for (int pe = 0; pe < g.peCount(); ++pe) {
      glm::dvec3 lo, hi;
      boxOf(g, pe, lo, hi);
      std::vector<int> want, got;
      for (const GrTriangle& t : b.triangles) {
        glm::dvec3 v[3];
        triangleVertices(t, v);
        if (triangleOverlapsBox(lo - g.margin, hi + g.margin, v[0], v[1], v[2]))
          want.push_back(t.prim);
      }
      for (int k = g.pe_tri_begin[pe]; k < g.pe_tri_begin[pe + 1]; ++k)
        got.push_back(g.pe_triangles[k].prim);
      EXPECT_TRUE(std::is_sorted(got.begin(), got.end())) << "PE " << pe;
      wrong += want != got;
    }
    EXPECT_EQ(wrong, 0u) << "leaf " << leaf << ": " << g.peCount() << " PEs";
  }
}

TEST(AdaptiveGrid, LeavesDoNotOverlap) {
  const Built b = build(10.0f, 16);
  const UniformGrid& g = b.grid;
  size_t overlaps = 0;
  for (int p = 0; p < g.peCount(); ++p)
    for (int q = p + 1; q < g.peCount(); ++q) {
      glm::dvec3 plo, phi, qlo, qhi;
      boxOf(g, p, plo, phi);
      boxOf(g, q, qlo, qhi);
      bool apart = false;
      for (int a = 0; a < 3; ++a) apart = apart || phi[a] <= qlo[a] || qhi[a] <= plo[a];
      overlaps += !apart;
    }
  EXPECT_EQ(overlaps, 0u);
}

// A grid below a cell never splits an axis into cells narrower than kMinCellMargins grid
// margins: on a floor 10,000 times the model (margin 0.03 around a model 0.15 wide) the
// model's cell is still refined, but not into cells the margin would fill (without the
// limit 12 of its 28 split axes are).
TEST(AdaptiveGrid, NoGridBelowACellSplitsItFinerThanItsMargin) {
  const Built b = build(10000.0f, 16);
  const UniformGrid& g = b.grid;
  ASSERT_GE(g.adaptive.depth, 1);
  int split_axes = 0, too_fine = 0;
  for (const GridNode& n : g.adaptive.nodes)
    for (int a = 0; a < 3; ++a) {
      if (n.dims[a] == 1) continue;
      ++split_axes;
      const double extent = double(g.adaptive.planes[n.plane_begin[a] + n.dims[a]]) -
                            double(g.adaptive.planes[n.plane_begin[a]]);
      too_fine += n.dims[a] * kMinCellMargins * g.margin > extent;
    }
  EXPECT_GT(split_axes, 0);
  EXPECT_EQ(too_fine, 0) << "of " << split_axes << " split axes, margin " << g.margin;
}

// A flat square of nx x nz quads on [48, 52] x {50} x [48, 52], with two tiny triangles
// spanning [0, 100]^3 so that the square lies alone in a cell of the top grid: the count
// of the PEs holding it, their references and the fullest's count.
struct SquareLeaves {
  size_t pes = 0, references = 0;
  int fullest = 0;
};
SquareLeaves squareInACell(int nx, int nz, const GridSettings& settings) {
  Scene scene;
  for (int i = 0; i < nx; ++i)
    for (int j = 0; j < nz; ++j) {
      const float x0 = 48.0f + 4.0f * i / nx, x1 = 48.0f + 4.0f * (i + 1) / nx;
      const float z0 = 48.0f + 4.0f * j / nz, z1 = 48.0f + 4.0f * (j + 1) / nz;
      const glm::vec3 a(x0, 50.0f, z0), b(x1, 50.0f, z0), c(x1, 50.0f, z1), d(x0, 50.0f, z1);
      scene.positions.insert(scene.positions.end(), {a, b, c, a, c, d});
    }
  for (float corner : {0.0f, 100.0f})
    scene.positions.insert(scene.positions.end(), {glm::vec3(corner), glm::vec3(corner + 0.01f),
                                                   glm::vec3(corner, corner, corner + 0.01f)});
  const std::vector<GrTriangle> triangles = prepareTriangles(scene);
  const UniformGrid g = buildAdaptiveGrid(triangles, sceneBounds(scene), settings);
  EXPECT_GE(g.adaptive.depth, 1);
  SquareLeaves s;
  for (int pe = 0; pe < g.peCount(); ++pe) {
    const int count = g.triangleCountOfPe(pe);
    if (g.pe_triangles[g.pe_tri_begin[pe]].prim >= 2 * nx * nz) continue;  // a corner's
    ++s.pes;
    s.references += size_t(count);
    s.fullest = std::max(s.fullest, count);
  }
  return s;
}

// Below a full cell lies a piece of surface: its grid is fitted to a surface crossing it
// (about kSurfaceCellShare of the leaf limit in each cell the surface passes through), not
// to a volume. A square of 20,000 triangles: its leaves hold on average more than a quarter
// of the limit (the volume rule, the cube root of density * count, split its cells of ~430
// in 3 x 3 x 3, leaving ~48 each), and none more than the limit. A square of 270 triangles,
// just over the limit, is split too (the resolution rounded up, not to the nearest: 1.45
// cells per axis would have kept it whole).
TEST(AdaptiveGrid, AGridBelowAFullCellFitsTheSurfaceItHolds) {
  GridSettings settings;
  settings.structure = GridStructure::Adaptive;
  const SquareLeaves large = squareInACell(100, 100, settings);
  ASSERT_GT(large.pes, 0u);
  EXPECT_GT(double(large.references) / double(large.pes), settings.max_leaf_triangles / 4.0)
      << large.pes << " PEs hold the square";
  EXPECT_LE(large.fullest, settings.max_leaf_triangles);
  const SquareLeaves small = squareInACell(15, 9, settings);
  EXPECT_GT(small.pes, 1u);
  EXPECT_LE(small.fullest, settings.max_leaf_triangles);
}

// Rays from random points of the box in random directions, some along the axes: at 64
// distances along each ray, a point inside a leaf (away from its faces by the grid's
// margin) lies in an entry of that leaf, and every entry's leaf, grown by the margin,
// holds the middle of the entry's interval.
TEST(AdaptiveGrid, ListsPutEveryPointOfTheRayInsideALeafInThatLeafsEntry) {
  for (int leaf : {256, 16}) {
    const Built b = build(10.0f, leaf);
    const UniformGrid& g = b.grid;
    const double m = g.margin;
    glm::dvec3 glo(g.info.minx, g.info.miny, g.info.minz);
    glm::dvec3 ghi =
        glo + glm::dvec3(g.info.nx * double(g.info.cellx), g.info.ny * double(g.info.celly),
                         g.info.nz * double(g.info.cellz));
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> unit(0.0, 1.0), signed_unit(-1.0, 1.0);
    size_t missed = 0, stray = 0, checked = 0;
    std::vector<ListEntry> list;
    for (int r = 0; r < 3000; ++r) {
      glm::dvec3 o = glo + glm::dvec3(unit(rng), unit(rng), unit(rng)) * (ghi - glo);
      glm::dvec3 d(signed_unit(rng), signed_unit(rng), signed_unit(rng));
      if (r % 10 == 0) d[r / 10 % 3] = 0.0;                       // in a plane of two axes
      if (r % 30 == 1) d = glm::dvec3(0.0), d[r / 30 % 3] = 1.0;  // along an axis
      if (glm::length(d) < 0.1) continue;
      d = glm::normalize(d);
      const GrRay ray{float(o.x), float(o.y), float(o.z), 0.0f,
                      float(d.x), float(d.y), float(d.z), 1e30f};
      list.clear();
      adaptiveList(g, ray, list);
      for (size_t k = 1; k < list.size(); ++k)
        EXPECT_LE(list[k - 1].t_exit, list[k].t_enter) << "ray " << r;
      const glm::dvec3 fo(ray.ox, ray.oy, ray.oz), fd(ray.dx, ray.dy, ray.dz);
      for (const ListEntry& e : list) {
        glm::dvec3 lo, hi;
        boxOf(g, e.pe, lo, hi);
        const double t = 0.5 * (double(e.t_enter) + double(e.t_exit));
        stray += !inside(fo + t * fd, lo, hi, m);
      }
      const double span = glm::length(ghi - glo);
      for (int s = 0; s < 64; ++s) {
        const float t = float(span * (s + 0.5) / 64.0);
        const glm::dvec3 p = fo + double(t) * fd;
        for (int pe = 0; pe < g.peCount(); ++pe) {
          glm::dvec3 lo, hi;
          boxOf(g, pe, lo, hi);
          if (!inside(p, lo, hi, -m)) continue;
          ++checked;
          bool found = false;
          for (const ListEntry& e : list)
            found = found || (e.pe == pe && e.t_enter <= t && t <= e.t_exit);
          missed += !found;
        }
      }
    }
    EXPECT_GT(checked, 1000u);
    EXPECT_EQ(missed, 0u) << "leaf " << leaf;
    EXPECT_EQ(stray, 0u) << "leaf " << leaf;
  }
}

// The batch lists (the top grid walked a packet of rays at a time) equal the one-ray walk
// entry for entry, bit for bit: rays from inside and outside the box, along axes, with a
// subnormal or a zero direction component, through a grid vertex, and not finite.
TEST(AdaptiveGrid, BatchListsEqualTheOneRayWalk) {
  for (int leaf : {256, 16}) {
    const Built b = build(10.0f, leaf);
    const UniformGrid& g = b.grid;
    ASSERT_FALSE(g.adaptive.empty());
    const glm::vec3 lo(g.info.minx, g.info.miny, g.info.minz);
    const glm::vec3 size(g.info.nx * g.info.cellx, g.info.ny * g.info.celly,
                         g.info.nz * g.info.cellz);
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> unit(-0.5f, 1.5f), dir(-1.0f, 1.0f);
    std::vector<GrRay> rays;
    for (int r = 0; r < 5000; ++r) {
      glm::vec3 o = lo + glm::vec3(unit(rng), unit(rng), unit(rng)) * size;
      glm::vec3 d(dir(rng), dir(rng), dir(rng));
      if (r % 7 == 1) d[r % 3] = 0.0f;
      if (r % 7 == 2) d = glm::vec3(0.0f), d[r % 3] = r % 2 ? 1.0f : -1.0f;
      if (r % 7 == 3) d[(r + 1) % 3] = 1e-40f;                  // subnormal: walks as 0
      if (r % 7 == 4) o = lo + glm::vec3(0.5f) * size, d = -d;  // through the middle
      rays.push_back(GrRay{o.x, o.y, o.z, 0.0f, d.x, d.y, d.z, 1e30f});
    }
    rays.push_back(GrRay{NAN, 0.0f, 0.0f, 0.0f, 1.0f, 0.0f, 0.0f, 1e30f});
    rays.push_back(GrRay{0.0f, 0.0f, 0.0f, 0.0f, INFINITY, 0.0f, 0.0f, 1e30f});
    TraversalLists lists;
    computeAdaptiveLists(g, rays.data(), rays.size(), lists);
    ASSERT_EQ(lists.rayCount(), rays.size());
    size_t differ = 0, entries = 0;
    std::vector<ListEntry> one;
    for (size_t r = 0; r < rays.size(); ++r) {
      one.clear();
      adaptiveList(g, rays[r], one);
      entries += one.size();
      bool same = int(one.size()) == lists.lengthOf(r);
      for (int k = 0; same && k < lists.lengthOf(r); ++k) {
        const ListEntry& e = lists.entriesOf(r)[k];
        same = e.pe == one[k].pe && std::memcmp(&e.t_enter, &one[k].t_enter, 4) == 0 &&
               std::memcmp(&e.t_exit, &one[k].t_exit, 4) == 0;
      }
      differ += !same;
    }
    EXPECT_GT(entries, rays.size() / 2);
    EXPECT_EQ(differ, 0u) << "leaf " << leaf;
  }
}

}  // namespace
}  // namespace gridrt
