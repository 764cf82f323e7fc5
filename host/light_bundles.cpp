#include "light_bundles.h"

#include <omp.h>

#include <algorithm>
#include <cmath>

namespace gridrt {

namespace {

// The two axes spanning the faces of cube axis a.
constexpr int kOtherAxes[3][2] = {{1, 2}, {2, 0}, {0, 1}};

// The cell of direction w (from the light): face 2 * axis + (w[axis] < 0), then row and
// column of (w[b], w[c]) / |w[axis]| in [-1, 1]^2.
int cellOf(const glm::vec3& w, int res) {
  const glm::vec3 m = glm::abs(w);
  const int a = m.x >= m.y && m.x >= m.z ? 0 : (m.y >= m.z ? 1 : 2);
  const float major = m[a];
  auto index = [&](float x) {  // float clamp first: NaN and huge values stay in range
    float i = (x / major + 1.0f) * 0.5f * float(res);
    return int(std::max(0.0f, std::min(float(res - 1), i)));
  };
  if (!(major > 0.0f)) return 0;
  const int face = 2 * a + (w[a] < 0.0f);
  return (face * res + index(w[kOtherAxes[a][1]])) * res + index(w[kOtherAxes[a][0]]);
}

}  // namespace

int lightCubeResolution(size_t count) {
  return std::max(8, std::min(1024, int(std::sqrt(double(count) / 16.0))));
}

void bundleLightRays(const UniformGrid& grid, const glm::vec3& light, const GrRay* rays,
                     size_t count, RayBundles& bundles, LightBundleScratch& scratch) {
  const int res = lightCubeResolution(count);
  const int rows = 6 * res;
  const size_t cells = size_t(rows) * res;

  // Each ray's cell, and how far its end lies from the light.
  scratch.cell_of.resize(count);
  float miss = 0.0f;
#pragma omp parallel for schedule(static) reduction(max : miss)
  for (long long r = 0; r < (long long)count; ++r) {
    const GrRay& ray = rays[r];
    const glm::vec3 d(ray.dx, ray.dy, ray.dz);
    const glm::vec3 end = glm::vec3(ray.ox, ray.oy, ray.oz) + ray.tmax * d;
    const float off = glm::length(end - light);
    miss = std::max(miss, std::isfinite(off) ? off : INFINITY);
    scratch.cell_of[r] = cellOf(-d, res);
  }
  // Bundle order: counting sort by cell (stable), padded to whole packets.
  std::vector<int>& start = scratch.cell_start;
  start.assign(cells + 1, 0);
  for (size_t r = 0; r < count; ++r) ++start[scratch.cell_of[r] + 1];
  for (size_t c = 0; c < cells; ++c) start[c + 1] += start[c];
  bundles.ray_of.assign((count + kBundleLanes - 1) / kBundleLanes * kBundleLanes, -1);
  {
    std::vector<int> next(start.begin(), start.end() - 1);
    for (size_t r = 0; r < count; ++r) bundles.ray_of[next[scratch.cell_of[r]]++] = int(r);
  }

  // Boxes are grown by the rays' largest miss of the light (rounding of the corners'
  // projections is covered by the cell margin below).
  const GrGridInfo& g = grid.info;
  const float slack = kLightSlackFactor * miss;

  const int pes = grid.peCount();
  const int threads = omp_get_max_threads();
  scratch.thread_runs.resize(threads);
#pragma omp parallel num_threads(threads)
  {
    auto& runs = scratch.thread_runs[omp_get_thread_num()];
    runs.clear();
    auto addRow = [&](int pe, int row, int c0, int c1) {
      const int first = start[size_t(row) * res + c0], last = start[size_t(row) * res + c1];
      if (last > first) runs.push_back(LightBundleScratch::Run{pe, row, first, last - first});
    };
#pragma omp for schedule(static)
    for (int pe = 0; pe < pes; ++pe) {
      const glm::ivec3 v = grid.voxelCoords(grid.voxel_of_pe[pe]);
      const glm::vec3 lo = glm::vec3(g.minx + float(v.x) * g.cellx, g.miny + float(v.y) * g.celly,
                                     g.minz + float(v.z) * g.cellz) - slack;
      const glm::vec3 hi = glm::vec3(g.minx + float(v.x + 1) * g.cellx,
                                     g.miny + float(v.y + 1) * g.celly,
                                     g.minz + float(v.z + 1) * g.cellz) + slack;
      if (!std::isfinite(slack)) {  // rays that do not end anywhere near the light
        for (int row = 0; row < rows; ++row) addRow(pe, row, 0, res);
        continue;
      }
      for (int face = 0; face < 6; ++face) {
        const int a = face / 2, b = kOtherAxes[a][0], c = kOtherAxes[a][1];
        const float s = face % 2 ? -1.0f : 1.0f;
        // The part of the box in front of the face (depth s * (x_a - light_a) >= 0).
        // Corners at depth 0 project to infinity (IEEE x / 0), so a box beside or around
        // the light reaches the face's borders; 0 / 0 (a corner on the light's axis line)
        // says nothing and is left out, its neighbours span that side.
        glm::vec3 blo = lo, bhi = hi;
        if (s > 0.0f) blo[a] = std::max(blo[a], light[a]);
        else bhi[a] = std::min(bhi[a], light[a]);
        if (!(blo[a] <= bhi[a])) continue;
        float umin = INFINITY, umax = -INFINITY, vmin = INFINITY, vmax = -INFINITY;
        for (int k = 0; k < 8; ++k) {
          const glm::vec3 p(k & 1 ? bhi.x : blo.x, k & 2 ? bhi.y : blo.y, k & 4 ? bhi.z : blo.z);
          // +0 on the light's plane (s * 0 may be -0, which would flip the infinities).
          const float depth = std::max(0.0f, s * (p[a] - light[a]));
          const float u = (p[b] - light[b]) / depth, w = (p[c] - light[c]) / depth;
          if (!std::isnan(u)) {
            umin = std::min(umin, u);
            umax = std::max(umax, u);
          }
          if (!std::isnan(w)) {
            vmin = std::min(vmin, w);
            vmax = std::max(vmax, w);
          }
        }
        // Cells, kLightCellMargin more on every side against rounding.
        auto cell = [&](float x) { return std::max(-1.0f, std::min(float(res), (x + 1.0f) * 0.5f * float(res))); };
        const int c0 = std::max(0, int(std::floor(cell(umin))) - kLightCellMargin);
        const int c1 = std::min(res, int(std::floor(cell(umax))) + 1 + kLightCellMargin);
        const int r0 = std::max(0, int(std::floor(cell(vmin))) - kLightCellMargin);
        const int r1 = std::min(res, int(std::floor(cell(vmax))) + 1 + kLightCellMargin);
        for (int r = r0; r < r1; ++r) addRow(pe, face * res + r, c0, c1);
      }
    }
  }
  // Tasks in cell-row order: neighbouring work-groups read neighbouring rays, and phase 2
  // updates one stretch of bundle order at a time.
  auto& row_start = scratch.row_start;
  row_start.assign(rows + 1, 0);
  for (const auto& runs : scratch.thread_runs)
    for (const auto& run : runs) ++row_start[run.row + 1];
  for (int r = 0; r < rows; ++r) row_start[r + 1] += row_start[r];
  scratch.sorted.resize(row_start[rows]);
  for (const auto& runs : scratch.thread_runs)
    for (const auto& run : runs) scratch.sorted[row_start[run.row]++] = run;
  bundles.clearTasks();
  for (const auto& run : scratch.sorted) bundles.addRange(run.pe, run.first, run.count);
}

}  // namespace gridrt
