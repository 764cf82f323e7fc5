// The PEs' hulls (host/grid/pe_hulls.h): each lies in its PE's box, holds every point of
// the box within the grid's margin of its triangles' bounds, and is no larger than that
// (so a floor's leaves become slabs). That the bundles keep every hit with them is
// checked against brute force by the uneven-scene and conformance suites.
#include "pe_hulls.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "adaptive_grid.h"
#include "gltf_loader.h"
#include "prepared_triangles.h"
#include "test_support.h"
#include "uneven_scenes.h"

namespace gridrt {
namespace {

struct Counts {
  int pes = 0, outside_box = 0, misses_triangles = 0, looser = 0, cut = 0;
};

// For every PE: box and hull as stored, and the region every hull must hold (the box cut
// to the triangles' bounds grown by the margin, in double).
Counts checkHulls(const UniformGrid& g) {
  Counts c;
  c.pes = g.peCount();
  for (int pe = 0; pe < g.peCount(); ++pe) {
    glm::vec3 blo, bhi, hlo, hhi;
    g.voxelBoxOfPe(pe, blo, bhi);
    g.hullOfPe(pe, hlo, hhi);
    glm::dvec3 lo(std::numeric_limits<double>::infinity()), hi(-lo);
    for (int k = g.pe_tri_begin[pe]; k < g.pe_tri_begin[pe + 1]; ++k) {
      glm::dvec3 v[3];
      triangleVertices(g.pe_triangles[k], v);
      for (const glm::dvec3& p : v) lo = glm::min(lo, p), hi = glm::max(hi, p);
    }
    bool outside = false, misses = false, looser = false, cut = false;
    for (int a = 0; a < 3; ++a) {
      outside = outside || hlo[a] < blo[a] || hhi[a] > bhi[a];
      const double need_lo = std::max(double(blo[a]), lo[a] - g.margin);
      const double need_hi = std::min(double(bhi[a]), hi[a] + g.margin);
      misses = misses || double(hlo[a]) > need_lo || double(hhi[a]) < need_hi;
      // No larger than the region rounded outwards to the next float.
      looser = looser || hlo[a] < std::nextafter(float(need_lo), -INFINITY) ||
               hhi[a] > std::nextafter(float(need_hi), INFINITY);
      cut = cut || hlo[a] > blo[a] || hhi[a] < bhi[a];
    }
    c.outside_box += outside;
    c.misses_triangles += misses;
    c.looser += looser;
    c.cut += cut;
  }
  return c;
}

TEST(PeHulls, HoldTheBoxWithinTheMarginOfTheTrianglesAndNoMore) {
  const Scene bunny = loadGltfFile(test::modelScene("bunny_res4.glb"));
  for (float scale : {0.0f, 100.0f}) {
    const Scene scene = scale > 0.0f ? floorScene(bunny, scale) : bunny;
    const std::vector<GrTriangle> triangles = prepareTriangles(scene);
    for (GridStructure structure : {GridStructure::Uniform, GridStructure::Adaptive}) {
      GridSettings s;
      s.structure = structure;
      s.max_leaf_triangles = 16;
      const UniformGrid g = buildGrid(triangles, sceneBounds(scene), s);
      ASSERT_EQ(g.pe_hull.size(), g.pe_box.size());
      const Counts c = checkHulls(g);
      SCOPED_TRACE(testing::Message() << "floor " << scale << ", structure " << int(structure)
                                      << ", " << c.pes << " PEs, " << c.cut << " cut");
      EXPECT_EQ(c.outside_box, 0);
      EXPECT_EQ(c.misses_triangles, 0);
      EXPECT_EQ(c.looser, 0);
      EXPECT_GT(c.cut, 0);
    }
  }
}

// On a floor 100 times the model, the leaves holding only the floor's triangles become slabs no
// thicker than the floor plus a margin on each side.
TEST(PeHulls, AFloorsLeavesBecomeSlabs) {
  const Scene bunny = loadGltfFile(test::modelScene("bunny_res4.glb"));
  const Scene scene = floorScene(bunny, 100.0f);
  const std::vector<GrTriangle> triangles = prepareTriangles(scene);
  GridSettings s;
  s.structure = GridStructure::Adaptive;
  const UniformGrid g = buildGrid(triangles, sceneBounds(scene), s);
  int floor_leaves = 0, slabs = 0;
  for (int pe = 0; pe < g.peCount(); ++pe) {
    bool floor_only = true;  // the floor's two triangles come after the model's
    for (int k = g.pe_tri_begin[pe]; k < g.pe_tri_begin[pe + 1]; ++k)
      floor_only = floor_only && g.pe_triangles[k].prim >= int(triangles.size()) - 2;
    if (!floor_only) continue;
    glm::vec3 blo, bhi, hlo, hhi;
    g.voxelBoxOfPe(pe, blo, bhi);
    g.hullOfPe(pe, hlo, hhi);
    ++floor_leaves;
    // Each face is rounded outwards to a float: under one ulp of its coordinate further.
    const double ulp = double(std::nextafter(hhi.y, INFINITY)) - double(hhi.y);
    slabs += double(hhi.y) - double(hlo.y) <= 2.0 * g.margin + 2.0 * ulp &&
             double(bhi.y) - double(blo.y) > 4.0 * g.margin;
  }
  EXPECT_GT(floor_leaves, 10);
  EXPECT_EQ(slabs, floor_leaves);
}

}  // namespace
}  // namespace gridrt
