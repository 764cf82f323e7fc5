#include "uniform_grid.h"

#include <algorithm>
#include <cmath>

#include "grid_dda.h"
#include "parallel_loops.h"
#include "pe_hulls.h"
#include "prefault.h"
#include "prepared_triangles.h"
#include "triangle_cells.h"
#include "triangle_gather.h"

namespace gridrt {

namespace {

struct VoxelRef {
  int voxel;
  int triangle;
};

}  // namespace

size_t UniformGrid::memoryBytes() const {
  return pe_of_voxel.size() * sizeof(int) + voxel_of_pe.size() * sizeof(int) +
         pe_tri_begin.size() * sizeof(int) + pe_triangles.size() * sizeof(GrTriangle) +
         (pe_box.size() + pe_hull.size()) * sizeof(float) + adaptive.top.size() * sizeof(int) +
         adaptive.nodes.size() * sizeof(GridNode) + adaptive.cells.size() * sizeof(int) +
         adaptive.planes.size() * sizeof(float);
}

void UniformGrid::hullOfPe(int pe, glm::vec3& lo, glm::vec3& hi) const {
  if (pe_hull.empty()) return voxelBoxOfPe(pe, lo, hi);
  const float* b = &pe_hull[size_t(pe) * 6];
  lo = glm::vec3(b[0], b[1], b[2]);
  hi = glm::vec3(b[3], b[4], b[5]);
}

void UniformGrid::voxelBoxOfPe(int pe, glm::vec3& lo, glm::vec3& hi) const {
  if (!pe_box.empty()) {
    const float* b = &pe_box[size_t(pe) * 6];
    lo = glm::vec3(b[0], b[1], b[2]);
    hi = glm::vec3(b[3], b[4], b[5]);
    return;
  }
  const glm::ivec3 v = voxelCoords(voxel_of_pe[pe]);
  const GrGridInfo& g = info;
  lo = glm::vec3(gr_grid_plane(g.minx, g.cellx, v.x), gr_grid_plane(g.miny, g.celly, v.y),
                 gr_grid_plane(g.minz, g.cellz, v.z));
  hi = glm::vec3(gr_grid_plane(g.minx, g.cellx, v.x + 1), gr_grid_plane(g.miny, g.celly, v.y + 1),
                 gr_grid_plane(g.minz, g.cellz, v.z + 1));
}

glm::ivec3 voxelCoordsIn(const GrGridInfo& info, int linear) {
  return {linear % info.nx, (linear / info.nx) % info.ny, linear / (info.nx * info.ny)};
}

glm::ivec3 UniformGrid::voxelCoords(int linear) const { return voxelCoordsIn(info, linear); }

AxisCells::AxisCells(const std::vector<float>& planes, double m)
    : planes_(planes.data()), cells_(int(planes.size()) - 1), p0_(planes[0]), m_(m) {
  // A billionth of the mean cell: far above double rounding, far below any cell.
  constexpr double kRangeSlack = 1e-9;
  const double mean = (double(planes[cells_]) - p0_) / cells_;
  cells_per_unit_ = 1.0 / mean;
  slack_ = kRangeSlack * mean;
}

void AxisCells::range(double lo, double hi, int& first, int& last) const {
  const int r = cells_;
  const float* planes = planes_;
  const double reach_lo = lo - m_ - slack_, reach_hi = hi + m_ + slack_;
  // The planes are about evenly spaced: start from the arithmetic guess (clamped before
  // the int conversion: NaN and far-off values) and step to the exact answer, a cell or
  // two at most (a binary search per triangle and axis made the row's build 20 % slower;
  // the guess multiplies by the cells per unit, where a division made this function a
  // tenth of the scattered scene's build).
  auto guess = [&](double x) {
    const double i = (x - p0_) * cells_per_unit_;
    return !(i >= 0.0) ? 0 : i >= double(r - 1) ? r - 1 : int(i);
  };
  // First cell whose upper face reaches lo.
  first = guess(reach_lo);
  while (first < r - 1 && double(planes[first + 1]) < reach_lo) ++first;
  while (first > 0 && double(planes[first]) >= reach_lo) --first;
  // Last cell whose lower face is below hi.
  last = guess(reach_hi);
  while (last < r - 1 && double(planes[last + 1]) <= reach_hi) ++last;
  while (last > 0 && double(planes[last]) > reach_hi) --last;
}

glm::ivec3 autoGridResolution(const Bounds& bounds, size_t triangle_count, float density) {
  glm::dvec3 d = bounds.empty() ? glm::dvec3(1.0) : glm::dvec3(bounds.extent());
  double largest = std::max({d.x, d.y, d.z});
  if (!(largest > 0.0)) return {1, 1, 1};
  d = glm::max(d, glm::dvec3(largest * 1e-3));
  double k = std::cbrt(double(density) * double(triangle_count) / (d.x * d.y * d.z));
  glm::ivec3 r;
  for (int a = 0; a < 3; ++a) r[a] = std::clamp(int(std::lround(d[a] * k)), 1, kMaxGridResolution);
  while ((long long)r.x * r.y * r.z > kMaxGridVoxels) r = glm::max(r / 2, glm::ivec3(1));
  return r;
}

UniformBins binUniformGrid(const std::vector<GrTriangle>& triangles, const Bounds& bounds,
                           const GridSettings& settings) {
  UniformBins grid;
  glm::ivec3 n = settings.automatic
                     ? autoGridResolution(bounds, triangles.size(), settings.density)
                     : glm::clamp(settings.dims, glm::ivec3(1), glm::ivec3(kMaxGridResolution));
  Bounds box = bounds;
  if (box.empty()) box.lo = box.hi = glm::vec3(0.0f);
  glm::dvec3 lo(box.lo), hi(box.hi);
  Bounds reach = box;  // the scene and the points rays start from
  if (!settings.ray_origins.empty()) {
    reach.grow(settings.ray_origins.lo);
    reach.grow(settings.ray_origins.hi);
  }
  // The longest way a ray takes through the grid (kGridMarginRel, uniform_grid.h).
  const double way = glm::length(glm::dvec3(reach.hi) - glm::dvec3(reach.lo));
  // A positive floor keeps the cells non-zero even for a scene collapsed to one point.
  grid.margin = std::max(settings.margin_rel * way, 1e-30);
  const glm::dvec3 gmin = lo - grid.margin;
  const glm::dvec3 cell = (hi - lo + 2.0 * grid.margin) / glm::dvec3(n);
  grid.info.minx = float(gmin.x);
  grid.info.miny = float(gmin.y);
  grid.info.minz = float(gmin.z);
  grid.info.cellx = float(cell.x);
  grid.info.celly = float(cell.y);
  grid.info.cellz = float(cell.z);
  grid.info.nx = n.x;
  grid.info.ny = n.y;
  grid.info.nz = n.z;
  // From here on the float values are the grid's definition (the DDA uses them).
  const double m = grid.margin;
  const size_t voxels = size_t(n.x) * n.y * n.z;
  // The voxels' faces as the 3D-DDA walks them (grid_dda.h: min + k * cell in float). Far
  // from the origin they lie up to half an ulp of the coordinates off min + k * cell in
  // double, far more than the margin: a triangle binned against the double planes could
  // touch a float one from a voxel the walk gives its hits to.
  std::vector<float> planes[3];
  const float mins[3] = {grid.info.minx, grid.info.miny, grid.info.minz};
  const float cells[3] = {grid.info.cellx, grid.info.celly, grid.info.cellz};
  for (int a = 0; a < 3; ++a) {
    planes[a].resize(size_t(n[a]) + 1);
    for (int k = 0; k <= n[a]; ++k) planes[a][k] = gr_grid_plane(mins[a], cells[a], k);
  }

  const AxisCells axis_cells[3] = {{planes[0], m}, {planes[1], m}, {planes[2], m}};
  std::vector<std::vector<VoxelRef>> refs(parallelSliceCount());
  parallelSlices(int(refs.size()), [&](int me, int count) {
    // Grown in a vector of the slice's own: pushing into refs[me] rewrote its end pointer,
    // on a cache line the other slices' vectors share, for every reference.
    std::vector<VoxelRef> mine;
    const auto [t_begin, t_end] = sliceRange(size_t(triangles.size()), me, count);
    for (size_t t = t_begin; t < t_end; ++t) {
      glm::dvec3 v[3];
      triangleVertices(triangles[t], v);
      forEachCellOfTriangle(v, axis_cells, planes, m, [&](int x, int y, int z) {
        mine.push_back({x + n.x * (y + n.y * z), int(t)});
      });
    }
    refs[me] = std::move(mine);
  });
  // Counting sort by voxel. Threads hold consecutive triangle ranges in order, so
  // walking thread 0, 1, ... keeps each voxel's triangles in increasing global index.
  std::vector<int> count(voxels, 0);
  for (const auto& list : refs)
    for (const auto& r : list) ++count[r.voxel];
  grid.pe_of_voxel.assign(voxels, -1);
  grid.pe_tri_begin.push_back(0);
  std::vector<int> cursor(voxels, 0);
  for (size_t v = 0; v < voxels; ++v) {
    if (count[v] == 0) continue;
    grid.pe_of_voxel[v] = int(grid.voxel_of_pe.size());
    grid.voxel_of_pe.push_back(int(v));
    cursor[v] = grid.pe_tri_begin.back();
    grid.pe_tri_begin.push_back(grid.pe_tri_begin.back() + count[v]);
  }
  grid.positions.resize(grid.pe_tri_begin.back());
  for (const auto& list : refs)
    for (const auto& r : list) grid.positions[cursor[r.voxel]++] = r.triangle;
  grid.info.pe_count = grid.peCount();
  return grid;
}

UniformGrid uniformGridOf(UniformBins&& bins, const std::vector<GrTriangle>& triangles) {
  UniformGrid grid;
  grid.info = bins.info;
  grid.margin = bins.margin;
  grid.triangle_count = triangles.size();
  grid.pe_of_voxel = std::move(bins.pe_of_voxel);
  grid.voxel_of_pe = std::move(bins.voxel_of_pe);
  grid.pe_tri_begin = std::move(bins.pe_tri_begin);
  reserveFaultedIn(grid.pe_triangles, bins.positions.size());  // on every core (prefault.h)
  grid.pe_triangles.resize(bins.positions.size());
  parallelSlices(parallelSliceCount(), [&](int me, int count) {
    const auto [first, last] = sliceRange(bins.positions.size(), me, count);
    gatherTriangles(triangles.data(), bins.positions.data() + first, last - first,
                    grid.pe_triangles.data() + first);
  });
  bins.positions = {};
  std::vector<float> boxes(size_t(grid.peCount()) * 6);  // voxelBoxOfPe from the voxels
  for (int pe = 0; pe < grid.peCount(); ++pe) {
    glm::vec3 blo, bhi;
    grid.voxelBoxOfPe(pe, blo, bhi);
    for (int a = 0; a < 3; ++a) {
      boxes[size_t(pe) * 6 + a] = blo[a];
      boxes[size_t(pe) * 6 + 3 + a] = bhi[a];
    }
  }
  grid.pe_box = std::move(boxes);
  grid.pe_hull = peHulls(grid);
  return grid;
}

UniformGrid buildUniformGrid(const std::vector<GrTriangle>& triangles, const Bounds& bounds,
                             const GridSettings& settings) {
  return uniformGridOf(binUniformGrid(triangles, bounds, settings), triangles);
}

}  // namespace gridrt
