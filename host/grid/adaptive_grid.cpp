#include "adaptive_grid.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <iterator>

#include "grid_dda.h"
#include "parallel_loops.h"
#include "pe_hulls.h"
#include "prefault.h"
#include "prepared_triangles.h"
#include "triangle_cells.h"
#include "triangle_gather.h"

namespace gridrt {

namespace {

struct Leaf {
  float box[6];                // lo x, y, z, hi x, y, z
  std::vector<int> triangles;  // positions in the input triangles, increasing
};

// A grid node over at least this many triangles sorts them into its cells on every thread
// (below it, the slices' start-up costs more than they save).
constexpr size_t kParallelNodeTriangles = 16384;

// One top cell's grids, numbered from 0 (spliced into the structure afterwards). Cell
// codes as in AdaptiveCells, with leaves and nodes numbered locally.
struct Subtree {
  std::vector<GridNode> nodes;
  std::vector<int> cells;
  std::vector<float> planes;
  std::vector<Leaf> leaves;
  int depth = 0;
};

// Appends the grid nodes, cells and planes of `part` to the arrays `nodes`, `cells`,
// `planes`, renumbering what refers into them; its leaves are numbered from `leaf_base`.
void appendGrids(std::vector<GridNode>& nodes, std::vector<int>& cells, std::vector<float>& planes,
                 const Subtree& part, int leaf_base) {
  const int node_base = int(nodes.size()), cell_base = int(cells.size());
  const int plane_base = int(planes.size());
  for (GridNode n : part.nodes) {
    n.cell_begin += cell_base;
    for (int k = 0; k < 3; ++k) n.plane_begin[k] += plane_base;
    nodes.push_back(n);
  }
  for (int code : part.cells)
    cells.push_back(code >= 0 ? code + leaf_base : code == -1 ? -1 : code - node_base);
  planes.insert(planes.end(), part.planes.begin(), part.planes.end());
}

// Appends `part` after what `tree` holds.
void appendSubtree(Subtree& tree, Subtree&& part) {
  appendGrids(tree.nodes, tree.cells, tree.planes, part, int(tree.leaves.size()));
  std::move(part.leaves.begin(), part.leaves.end(), std::back_inserter(tree.leaves));
  tree.depth = std::max(tree.depth, part.depth);
  part = Subtree{};
}

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

// The resolution of a grid below a cell holding `count` triangles in the box of extents d:
// the one at which a surface crossing the box along its largest face leaves about
// `per_cell` triangles in each cell it passes through, r_i = d_i * sqrt(count / (per_cell *
// A)) with A that face's area (each at least 1, within the uniform grid's limits). The
// triangles below a full cell are a piece of surface, not a volume: the uniform grid's
// volume rule (cube root of density * count) split a cell of 320 bunny triangles into 27
// cells of 12 and made the scattered copies' 25,252 PEs of 42 triangles; this rule makes
// 6,881 of 118 (docs/adaptive-grid.md). Rounded up: a cell just over the limit is split.
glm::ivec3 surfaceGridResolution(const double d[3], size_t count, double per_cell) {
  const double area = std::max({d[0] * d[1], d[1] * d[2], d[2] * d[0]});
  if (!(area > 0.0)) return {1, 1, 1};
  const double k = std::sqrt(double(count) / (per_cell * area));
  glm::ivec3 r;
  for (int a = 0; a < 3; ++a) r[a] = std::clamp(int(std::ceil(d[a] * k)), 1, kMaxGridResolution);
  while ((long long)r.x * r.y * r.z > kMaxGridVoxels) r = glm::max(r / 2, glm::ivec3(1));
  return r;
}

// A grid over the box [lo, hi] for the triangles at positions ids[0 .. id_count) of
// `base` (increasing, all overlapping the box grown by m), its cells' leaves and grids
// below them appended to `tree` in cell order (the grids below built in parallel, then
// appended in that order, so the numbering is the same on any number of threads); returns
// the node's local index, or -1 when the resolution is one cell (the box stays a leaf).
int buildNode(const float lo[3], const float hi[3], const GrTriangle* base, const int* ids,
              size_t id_count, int depth, double m, int max_leaf, Subtree& tree) {
  const double extent[3] = {double(hi[0]) - lo[0], double(hi[1]) - lo[1], double(hi[2]) - lo[2]};
  glm::ivec3 want = surfaceGridResolution(extent, id_count, kSurfaceCellShare * max_leaf);
  for (int a = 0; a < 3; ++a) {  // cells of at least kMinCellMargins margins
    const double fit = (double(hi[a]) - lo[a]) / (kMinCellMargins * m);
    if (fit < want[a]) want[a] = std::max(1, int(fit));
  }
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

  // Triangles per cell, in the input's (increasing global) order: (cell, triangle) pairs
  // found in consecutive slices of the triangles (in parallel when there are many: a model
  // alone in one top cell), then sorted by cell, slice by slice.
  struct CellRef {
    int cell;
    int triangle;
  };
  const AxisCells axis_cells[3] = {{planes[0], m}, {planes[1], m}, {planes[2], m}};
  const int slices = id_count >= kParallelNodeTriangles ? parallelSliceCount() : 1;
  std::vector<std::vector<CellRef>> refs(slices);
  parallelSlices(slices, [&](int me, int count) {
    // Grown in a vector of the slice's own: pushing into refs[me] rewrote its end pointer,
    // on a cache line the other slices' vectors share, for every reference.
    std::vector<CellRef> mine;
    const auto [t_begin, t_end] = sliceRange(id_count, me, count);
    for (size_t t = t_begin; t < t_end; ++t) {
      if (t + kTrianglePrefetchAhead < t_end)
        prefetchTriangle(base, ids[t + kTrianglePrefetchAhead]);
      glm::dvec3 v[3];
      triangleVertices(base[ids[t]], v);
      const int id = ids[t];
      forEachCellOfTriangle(v, axis_cells, planes, m, [&](int x, int y, int z) {
        mine.push_back({x + r[0] * (y + r[1] * z), id});
      });
    }
    refs[me] = std::move(mine);
  });
  std::vector<int> count(cells, 0);
  for (const auto& list : refs)
    for (const CellRef& ref : list) ++count[ref.cell];
  std::vector<std::vector<int>> in(cells);
  for (int c = 0; c < cells; ++c) in[c].reserve(count[c]);
  for (const auto& list : refs)
    for (const CellRef& ref : list) in[ref.cell].push_back(ref.triangle);
  refs = {};

  // The cells' boxes (faces on this grid's planes).
  auto cellBox = [&](int c, float clo[3], float chi[3]) {
    const int x = c % r[0], y = (c / r[0]) % r[1], z = c / (r[0] * r[1]);
    clo[0] = planes[0][x], clo[1] = planes[1][y], clo[2] = planes[2][z];
    chi[0] = planes[0][x + 1], chi[1] = planes[1][y + 1], chi[2] = planes[2][z + 1];
  };
  // The full cells' grids, each into a subtree of its own, in parallel.
  std::vector<int> full;
  for (int c = 0; c < cells; ++c)
    if (int(in[c].size()) > max_leaf && depth < kMaxAdaptiveDepth) full.push_back(c);
  std::vector<Subtree> below(full.size());
  std::vector<char> split(full.size(), 0);
  parallelForDynamic(size_t(0), full.size(), size_t(1), [&](size_t k) {
    float clo[3], chi[3];
    cellBox(full[k], clo, chi);
    split[k] = buildNode(clo, chi, base, in[full[k]].data(), in[full[k]].size(), depth + 1, m,
                         max_leaf, below[k]) >= 0;
  });
  for (int c = 0, k = 0; c < cells; ++c) {
    if (in[c].empty()) continue;
    if (k < int(full.size()) && full[k] == c) {
      const bool has_grid = split[k];
      Subtree& part = below[k++];
      if (has_grid) {
        tree.cells[n.cell_begin + c] = -(int(tree.nodes.size()) + 2);  // part's node 0
        appendSubtree(tree, std::move(part));
        continue;
      }
    }
    tree.cells[n.cell_begin + c] = int(tree.leaves.size());
    Leaf leaf;
    cellBox(c, leaf.box, leaf.box + 3);
    leaf.triangles = std::move(in[c]);
    tree.leaves.push_back(std::move(leaf));
  }
  return node;
}

// Triangle positions, increasing: the union of merged cells.
using TriangleSet = std::vector<int>;

void unite(TriangleSet& set, const int* first, const int* last, TriangleSet& scratch) {
  scratch.clear();
  std::set_union(set.begin(), set.end(), first, last, std::back_inserter(scratch));
  set.swap(scratch);
}

}  // namespace

namespace {

// The uniform grid of the automatic resolution under the settings' density and margin.
UniformBins topGrid(const std::vector<GrTriangle>& triangles, const Bounds& bounds,
                    const GridSettings& settings) {
  GridSettings top_settings = settings;
  top_settings.automatic = true;
  top_settings.structure = GridStructure::Uniform;
  return binUniformGrid(triangles, bounds, top_settings);
}

bool hasFullVoxel(const UniformBins& grid, int max_leaf_triangles) {
  for (int pe = 0; pe < grid.peCount(); ++pe)
    if (grid.triangleCountOfPe(pe) > max_leaf_triangles) return true;
  return false;
}

}  // namespace

UniformGrid buildAdaptiveGrid(const std::vector<GrTriangle>& triangles, const Bounds& bounds,
                              const GridSettings& settings) {
  return adaptiveGridOver(topGrid(triangles, bounds, settings), triangles, settings);
}

UniformGrid adaptiveGridOver(const UniformBins& top, const std::vector<GrTriangle>& triangles,
                             const GridSettings& settings) {
  const GrGridInfo& g = top.info;
  const int top_pes = top.peCount();
  auto plane = [&](int a, int k) {
    const float mins[3] = {g.minx, g.miny, g.minz}, cells[3] = {g.cellx, g.celly, g.cellz};
    return gr_grid_plane(mins[a], cells[a], k);
  };
  auto topPositions = [&](int pe) { return top.positions.data() + top.pe_tri_begin[pe]; };

  // The top cells over the limit get their grids, in parallel.
  std::vector<Subtree> trees(top_pes);
  std::vector<char> split(top_pes, 0);
  parallelForDynamic(int(0), int(top_pes), int(1), [&](int pe) {
    if (top.triangleCountOfPe(pe) <= settings.max_leaf_triangles) return;
    const glm::ivec3 v = voxelCoordsIn(g, top.voxel_of_pe[pe]);
    const float lo[3] = {plane(0, v.x), plane(1, v.y), plane(2, v.z)};
    const float hi[3] = {plane(0, v.x + 1), plane(1, v.y + 1), plane(2, v.z + 1)};
    split[pe] =
        buildNode(lo, hi, triangles.data(), topPositions(pe), size_t(top.triangleCountOfPe(pe)), 1,
                  top.margin, settings.max_leaf_triangles, trees[pe]) >= 0;
  });

  UniformGrid grid;
  grid.info = top.info;
  grid.margin = top.margin;
  grid.triangle_count = triangles.size();
  AdaptiveCells& a = grid.adaptive;
  a.top.assign(top.pe_of_voxel.size(), -1);
  // Room for every leaf at once: growing these arrays leaf by leaf copied and faulted in
  // megabytes.
  size_t leaf_count = size_t(top_pes);
  for (const Subtree& t : trees) leaf_count += t.leaves.size();
  grid.pe_box.reserve(leaf_count * 6);
  grid.pe_tri_begin.reserve(leaf_count + 1);
  grid.pe_tri_begin.push_back(0);
  // The merged top leaves' triangle positions, one after another in PE order (so PE p's
  // are merged_positions[pe_tri_begin[p] .. pe_tri_begin[p + 1])).
  std::vector<int> merged_positions;
  merged_positions.reserve(top.positions.size());
  auto addPe = [&](const float box[6], const TriangleSet& set) {
    grid.pe_box.insert(grid.pe_box.end(), box, box + 6);
    merged_positions.insert(merged_positions.end(), set.begin(), set.end());
    grid.pe_tri_begin.push_back(int(merged_positions.size()));
    return int(grid.pe_tri_begin.size()) - 2;
  };

  // Top leaves merged greedily into boxes (along x, then whole rows along y, then whole
  // layers along z) while the box's triangles stay the same set or at most
  // kMergeMaxTriangles: a floor's or a wall's cells hold one or both of its two triangles.
  const int nx = g.nx, ny = g.ny, nz = g.nz;
  std::vector<char> taken(top.pe_of_voxel.size(), 0);
  TriangleSet set, grown, scratch;
  auto cellTriangles = [&](int v, const int*& first, const int*& last) {
    const int pe = top.pe_of_voxel[v];
    if (pe < 0 || split[pe] || taken[v]) return false;
    first = topPositions(pe);
    last = topPositions(pe + 1);
    return true;
  };
  // Whether the cells [x0, x1) x [y0, y1) x [z0, z1) join `set` (into `grown`).
  auto joins = [&](int x0, int x1, int y0, int y1, int z0, int z1) {
    grown = set;
    bool same = true;
    for (int z = z0; z < z1; ++z)
      for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x) {
          const int *first, *last;
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
        const int *first, *last;
        if (!cellTriangles(v, first, last)) continue;  // empty, split or merged already
        set.assign(first, last);
        int x1 = x + 1, y1 = y + 1, z1 = z + 1;
        while (x1 < nx && joins(x1, x1 + 1, y, y1, z, z1)) set.swap(grown), ++x1;
        while (y1 < ny && joins(x, x1, y1, y1 + 1, z, z1)) set.swap(grown), ++y1;
        while (z1 < nz && joins(x, x1, y, y1, z1, z1 + 1)) set.swap(grown), ++z1;
        const float box[6] = {plane(0, x),  plane(1, y),  plane(2, z),
                              plane(0, x1), plane(1, y1), plane(2, z1)};
        const int id = addPe(box, set);
        for (int zz = z; zz < z1; ++zz)
          for (int yy = y; yy < y1; ++yy)
            for (int xx = x; xx < x1; ++xx) {
              const int w = xx + nx * (yy + ny * zz);
              taken[w] = 1;
              a.top[w] = id;
            }
      }
  const int merged_pes = grid.peCount();
  // The grids below the split cells, spliced in voxel order.
  std::vector<const Leaf*> leaves;
  for (int pe = 0; pe < top_pes; ++pe) {
    if (!split[pe]) continue;
    Subtree& t = trees[pe];
    const int node_base = int(a.nodes.size());
    appendGrids(a.nodes, a.cells, a.planes, t, grid.peCount());
    for (const Leaf& leaf : t.leaves) {
      grid.pe_box.insert(grid.pe_box.end(), leaf.box, leaf.box + 6);
      grid.pe_tri_begin.push_back(grid.pe_tri_begin.back() + int(leaf.triangles.size()));
      leaves.push_back(&leaf);
    }
    a.top[top.voxel_of_pe[pe]] = -(node_base + 2);
    a.depth = std::max(a.depth, t.depth);
  }
  // Every PE's triangles copied from the input once, in parallel, into memory faulted in
  // on every core (prefault.h: 50 MB for the scattered copies).
  const size_t total = size_t(grid.pe_tri_begin.back());
  reserveFaultedIn(grid.pe_triangles, total);
  grid.pe_triangles.resize(total);
  parallelForDynamic(int(0), grid.peCount(), int(64), [&](int pe) {
    const int* from = pe < merged_pes ? merged_positions.data() + grid.pe_tri_begin[pe]
                                      : leaves[pe - merged_pes]->triangles.data();
    gatherTriangles(triangles.data(), from, size_t(grid.triangleCountOfPe(pe)),
                    grid.pe_triangles.data() + grid.pe_tri_begin[pe]);
  });
  trees = {};
  grid.info.pe_count = grid.peCount();
  grid.pe_hull = peHulls(grid);
  return grid;
}

UniformGrid buildGrid(const std::vector<GrTriangle>& triangles, const Bounds& bounds,
                      const GridSettings& settings) {
  if (!settings.automatic || settings.structure == GridStructure::Uniform)
    return buildUniformGrid(triangles, bounds, settings);
  UniformBins top = topGrid(triangles, bounds, settings);
  if (settings.structure == GridStructure::WhereNeeded &&
      !hasFullVoxel(top, settings.max_leaf_triangles))
    return uniformGridOf(std::move(top), triangles);
  return adaptiveGridOver(top, triangles, settings);
}

}  // namespace gridrt
