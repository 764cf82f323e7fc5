#include "adaptive_grid.h"

#include <algorithm>
#include <cstdint>
#include <iterator>

#include "parallel_loops.h"
#include "prepared_triangles.h"
#include "triangle_box_overlap.h"

namespace gridrt {

namespace {

struct Leaf {
  float box[6];  // lo x, y, z, hi x, y, z
  std::vector<GrTriangle> triangles;
};

// One top cell's grids, numbered from 0 (spliced into the structure afterwards). Cell
// codes as in AdaptiveCells, with leaves and nodes numbered locally.
struct Subtree {
  std::vector<GridNode> nodes;
  std::vector<int> cells;
  std::vector<float> planes;
  std::vector<Leaf> leaves;
  int depth = 0;
};

// The planes of `r` equal cells between lo and hi (lo + k * ((hi - lo) / r) in float, the
// ends exactly lo and hi); 1 cell when rounding would not keep them increasing.
std::vector<float> axisPlanes(float lo, float hi, int r) {
  std::vector<float> p(size_t(r) + 1);
  const float cell = (hi - lo) / float(r);
  p[0] = lo;
  p[r] = hi;
  for (int k = 1; k < r; ++k) p[k] = lo + float(k) * cell;
  for (int k = 0; k < r; ++k)
    if (!(p[k] < p[k + 1])) return {lo, hi};
  return p;
}

// The cells [first, last] on one axis whose margin-grown extent [p[i] - m, p[i+1] + m]
// meets [lo, hi] (widened by one cell each side against rounding; the exact test decides).
void cellRange(const std::vector<float>& p, double lo, double hi, double m, int& first, int& last) {
  const int r = int(p.size()) - 1;
  first = int(std::lower_bound(p.begin() + 1, p.end(), float(lo - m)) - (p.begin() + 1));
  last = int(std::upper_bound(p.begin(), p.end() - 1, float(hi + m)) - p.begin()) - 1;
  first = std::clamp(first - 1, 0, r - 1);
  last = std::clamp(last + 1, 0, r - 1);
}

// A grid over the box [lo, hi] for `triangles` (all overlapping the box grown by m), its
// cells' leaves and grids below them appended to `tree`; returns the node's local index,
// or -1 when the resolution is one cell (the box stays a leaf).
int buildNode(const float lo[3], const float hi[3], const std::vector<GrTriangle>& triangles,
              int depth, double m, float density, int max_leaf, Subtree& tree) {
  Bounds box;
  box.lo = glm::vec3(lo[0], lo[1], lo[2]);
  box.hi = glm::vec3(hi[0], hi[1], hi[2]);
  const glm::ivec3 want = autoGridResolution(box, triangles.size(), density);
  std::vector<float> planes[3];
  for (int a = 0; a < 3; ++a) planes[a] = axisPlanes(lo[a], hi[a], want[a]);
  const int r[3] = {int(planes[0].size()) - 1, int(planes[1].size()) - 1,
                    int(planes[2].size()) - 1};
  if (r[0] * r[1] * r[2] <= 1) return -1;
  const int node = int(tree.nodes.size());
  tree.depth = std::max(tree.depth, depth);
  GridNode n{};
  for (int a = 0; a < 3; ++a) {
    n.dims[a] = r[a];
    n.plane_begin[a] = int(tree.planes.size());
    tree.planes.insert(tree.planes.end(), planes[a].begin(), planes[a].end());
  }
  const int cells = r[0] * r[1] * r[2];
  n.cell_begin = int(tree.cells.size());
  tree.nodes.push_back(n);
  tree.cells.resize(tree.cells.size() + cells, -1);

  // Triangles per cell, in the input's (increasing global) order.
  std::vector<std::vector<GrTriangle>> in(cells);
  for (const GrTriangle& t : triangles) {
    glm::dvec3 v[3];
    triangleVertices(t, v);
    const glm::dvec3 tlo = glm::min(v[0], glm::min(v[1], v[2]));
    const glm::dvec3 thi = glm::max(v[0], glm::max(v[1], v[2]));
    int first[3], last[3];
    for (int a = 0; a < 3; ++a) cellRange(planes[a], tlo[a], thi[a], m, first[a], last[a]);
    for (int z = first[2]; z <= last[2]; ++z)
      for (int y = first[1]; y <= last[1]; ++y)
        for (int x = first[0]; x <= last[0]; ++x) {
          const glm::dvec3 clo(double(planes[0][x]) - m, double(planes[1][y]) - m,
                               double(planes[2][z]) - m);
          const glm::dvec3 chi(double(planes[0][x + 1]) + m, double(planes[1][y + 1]) + m,
                               double(planes[2][z + 1]) + m);
          if (triangleOverlapsBox(clo, chi, v[0], v[1], v[2]))
            in[x + r[0] * (y + r[1] * z)].push_back(t);
        }
  }
  for (int z = 0; z < r[2]; ++z)
    for (int y = 0; y < r[1]; ++y)
      for (int x = 0; x < r[0]; ++x) {
        const int c = x + r[0] * (y + r[1] * z);
        if (in[c].empty()) continue;
        const float clo[3] = {planes[0][x], planes[1][y], planes[2][z]};
        const float chi[3] = {planes[0][x + 1], planes[1][y + 1], planes[2][z + 1]};
        int child = -1;
        if (int(in[c].size()) > max_leaf && depth < kMaxAdaptiveDepth)
          child = buildNode(clo, chi, in[c], depth + 1, m, density, max_leaf, tree);
        if (child >= 0) {
          tree.cells[n.cell_begin + c] = -(child + 2);
          continue;
        }
        tree.cells[n.cell_begin + c] = int(tree.leaves.size());
        Leaf leaf;
        std::copy(clo, clo + 3, leaf.box);
        std::copy(chi, chi + 3, leaf.box + 3);
        leaf.triangles = std::move(in[c]);
        tree.leaves.push_back(std::move(leaf));
      }
  return node;
}

// Triangles sorted by global index, as the union of merged cells.
using TriangleSet = std::vector<GrTriangle>;

void unite(TriangleSet& set, const GrTriangle* first, const GrTriangle* last,
           TriangleSet& scratch) {
  scratch.clear();
  std::set_union(set.begin(), set.end(), first, last, std::back_inserter(scratch),
                 [](const GrTriangle& a, const GrTriangle& b) { return a.prim < b.prim; });
  set.swap(scratch);
}

}  // namespace

namespace {

// The uniform grid of the automatic resolution under the settings' density and margin.
UniformGrid topGrid(const std::vector<GrTriangle>& triangles, const Bounds& bounds,
                    const GridSettings& settings) {
  GridSettings top_settings = settings;
  top_settings.automatic = true;
  top_settings.structure = GridStructure::Uniform;
  return buildUniformGrid(triangles, bounds, top_settings);
}

bool hasFullVoxel(const UniformGrid& grid, int max_leaf_triangles) {
  for (int pe = 0; pe < grid.peCount(); ++pe)
    if (grid.triangleCountOfPe(pe) > max_leaf_triangles) return true;
  return false;
}

}  // namespace

UniformGrid buildAdaptiveGrid(const std::vector<GrTriangle>& triangles, const Bounds& bounds,
                              const GridSettings& settings) {
  return adaptiveGridOver(topGrid(triangles, bounds, settings), settings);
}

UniformGrid adaptiveGridOver(const UniformGrid& top, const GridSettings& settings) {
  const GrGridInfo& g = top.info;
  const int top_pes = top.peCount();
  auto plane = [&](int a, int k) {
    const float mins[3] = {g.minx, g.miny, g.minz}, cells[3] = {g.cellx, g.celly, g.cellz};
    return mins[a] + float(k) * cells[a];  // the 3D-DDA's plane arithmetic
  };

  // The top cells over the limit get their grids, in parallel.
  std::vector<Subtree> trees(top_pes);
  std::vector<char> split(top_pes, 0);
  parallelForDynamic(int(0), int(top_pes), int(1), [&](int pe) {
    if (top.triangleCountOfPe(pe) <= settings.max_leaf_triangles) return;
    const glm::ivec3 v = top.voxelCoords(top.voxel_of_pe[pe]);
    const float lo[3] = {plane(0, v.x), plane(1, v.y), plane(2, v.z)};
    const float hi[3] = {plane(0, v.x + 1), plane(1, v.y + 1), plane(2, v.z + 1)};
    std::vector<GrTriangle> tris(top.pe_triangles.begin() + top.pe_tri_begin[pe],
                                 top.pe_triangles.begin() + top.pe_tri_begin[pe + 1]);
    split[pe] = buildNode(lo, hi, tris, 1, top.margin, settings.density,
                          settings.max_leaf_triangles, trees[pe]) >= 0;
  });

  UniformGrid grid;
  grid.info = top.info;
  grid.margin = top.margin;
  grid.triangle_count = top.triangle_count;
  AdaptiveCells& a = grid.adaptive;
  a.top.assign(top.voxelCount(), -1);
  grid.pe_tri_begin.push_back(0);
  auto addPe = [&](const float box[6], const GrTriangle* first, size_t count) {
    grid.pe_box.insert(grid.pe_box.end(), box, box + 6);
    grid.pe_triangles.insert(grid.pe_triangles.end(), first, first + count);
    grid.pe_tri_begin.push_back(int(grid.pe_triangles.size()));
    return int(grid.pe_tri_begin.size()) - 2;
  };

  // Top leaves merged greedily into boxes (along x, then whole rows along y, then whole
  // layers along z) while the box's triangles stay the same set or at most
  // kMergeMaxTriangles: a floor's or a wall's cells hold one or both of its two triangles.
  const int nx = g.nx, ny = g.ny, nz = g.nz;
  std::vector<char> taken(top.voxelCount(), 0);
  TriangleSet set, grown, scratch;
  auto cellTriangles = [&](int v, const GrTriangle*& first, const GrTriangle*& last) {
    const int pe = top.pe_of_voxel[v];
    if (pe < 0 || split[pe] || taken[v]) return false;
    first = top.pe_triangles.data() + top.pe_tri_begin[pe];
    last = top.pe_triangles.data() + top.pe_tri_begin[pe + 1];
    return true;
  };
  // Whether the cells [x0, x1) x [y0, y1) x [z0, z1) join `set` (into `grown`).
  auto joins = [&](int x0, int x1, int y0, int y1, int z0, int z1) {
    grown = set;
    bool same = true;
    for (int z = z0; z < z1; ++z)
      for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x) {
          const GrTriangle *first, *last;
          if (!cellTriangles(x + nx * (y + ny * z), first, last)) return false;
          same = same && size_t(last - first) == set.size();
          unite(grown, first, last, scratch);
          same = same && grown.size() == set.size();
          if (!same && grown.size() > size_t(kMergeMaxTriangles)) return false;
        }
    return true;
  };
  for (int z = 0; z < nz; ++z)
    for (int y = 0; y < ny; ++y)
      for (int x = 0; x < nx; ++x) {
        const int v = x + nx * (y + ny * z);
        const GrTriangle *first, *last;
        if (!cellTriangles(v, first, last)) continue;  // empty, split or merged already
        set.assign(first, last);
        int x1 = x + 1, y1 = y + 1, z1 = z + 1;
        while (x1 < nx && joins(x1, x1 + 1, y, y1, z, z1)) set.swap(grown), ++x1;
        while (y1 < ny && joins(x, x1, y1, y1 + 1, z, z1)) set.swap(grown), ++y1;
        while (z1 < nz && joins(x, x1, y, y1, z1, z1 + 1)) set.swap(grown), ++z1;
        const float box[6] = {plane(0, x),  plane(1, y),  plane(2, z),
                              plane(0, x1), plane(1, y1), plane(2, z1)};
        const int id = addPe(box, set.data(), set.size());
        for (int zz = z; zz < z1; ++zz)
          for (int yy = y; yy < y1; ++yy)
            for (int xx = x; xx < x1; ++xx) {
              const int w = xx + nx * (yy + ny * zz);
              taken[w] = 1;
              a.top[w] = id;
            }
      }
  // The grids below the split cells, spliced in voxel order.
  for (int pe = 0; pe < top_pes; ++pe) {
    if (!split[pe]) continue;
    Subtree& t = trees[pe];
    const int node_base = int(a.nodes.size()), cell_base = int(a.cells.size());
    const int plane_base = int(a.planes.size()), pe_base = int(grid.pe_tri_begin.size()) - 1;
    for (GridNode n : t.nodes) {
      n.cell_begin += cell_base;
      for (int k = 0; k < 3; ++k) n.plane_begin[k] += plane_base;
      a.nodes.push_back(n);
    }
    for (int code : t.cells)
      a.cells.push_back(code >= 0 ? code + pe_base : code == -1 ? -1 : code - node_base);
    a.planes.insert(a.planes.end(), t.planes.begin(), t.planes.end());
    for (const Leaf& leaf : t.leaves) addPe(leaf.box, leaf.triangles.data(), leaf.triangles.size());
    a.top[top.voxel_of_pe[pe]] = -(node_base + 2);
    a.depth = std::max(a.depth, t.depth);
    t = Subtree{};
  }
  grid.info.pe_count = grid.peCount();
  return grid;
}

UniformGrid buildGrid(const std::vector<GrTriangle>& triangles, const Bounds& bounds,
                      const GridSettings& settings) {
  if (!settings.automatic || settings.structure == GridStructure::Uniform)
    return buildUniformGrid(triangles, bounds, settings);
  UniformGrid top = topGrid(triangles, bounds, settings);
  if (settings.structure == GridStructure::WhereNeeded &&
      !hasFullVoxel(top, settings.max_leaf_triangles))
    return top;
  return adaptiveGridOver(top, settings);
}

}  // namespace gridrt
