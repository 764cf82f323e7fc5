#include "light_bundles.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "light_ray_scan.h"
#include "parallel_loops.h"

namespace gridrt {

namespace {

// How far coordinate x lies from the light's coordinate `light` along the axis of cube face
// `face`, outwards: a difference of floats taken in double, for a ray's origin and for a
// box's nearest face alike, so that the two compare as the points do.
double depthOnFace(float x, float light, int face) {
  return face % 2 ? double(light) - double(x) : double(x) - double(light);
}

// The bound kLightEndRoundingEpsilons puts on the rounding of an end within `reach`.
float endRoundingOf(float reach) {
  return kLightEndRoundingEpsilons * std::numeric_limits<float>::epsilon() * reach;
}

}  // namespace

void FaceWindow::add(float u, float v) {
  umin = std::min(umin, u);
  umax = std::max(umax, u);
  vmin = std::min(vmin, v);
  vmax = std::max(vmax, v);
  ++count;
}

void FaceWindow::merge(const FaceWindow& o) {
  umin = std::min(umin, o.umin);
  umax = std::max(umax, o.umax);
  vmin = std::min(vmin, o.vmin);
  vmax = std::max(vmax, o.vmax);
  count += o.count;
}

void FaceWindow::layout(int row, size_t cell) {
  first_row = row;
  first_cell = cell;
  res = count ? std::max(1, std::min(1024, int(std::sqrt(float(count) / kLightRaysPerCell)))) : 0;
  if (!res) return;
  // A window of zero width (one ray, or rays in a line) still gets a positive scale.
  u0 = umin;
  v0 = vmin;
  su = float(res) / std::max(umax - umin, 1e-6f);
  sv = float(res) / std::max(vmax - vmin, 1e-6f);
}

size_t FaceWindow::cellOf(float u, float v) const {
  auto index = [&](float x) {  // float clamp first: NaN and huge values stay in range
    return int(std::max(0.0f, std::min(float(res - 1), x)));
  };
  return first_cell + size_t(index((v - v0) * sv)) * res + index((u - u0) * su);
}

void FaceWindow::cellRange(float lo, float hi, float origin, float scale, int& c0, int& c1) const {
  // (x - origin) * scale is monotone in x, so the rays' cells (cellOf) and these agree.
  auto cell = [&](float x) {
    return std::floor(std::max(-1.0f, std::min(float(res), (x - origin) * scale)));
  };
  lo -= kLightFaceMargin * (1.0f + std::fabs(lo));
  hi += kLightFaceMargin * (1.0f + std::fabs(hi));
  c0 = std::max(0, int(cell(lo)));
  c1 = std::min(res, int(cell(hi)) + 1);
}

double originDepth(const GrRay& ray, const glm::vec3& light, int face) {
  const int a = face / 2;
  const float o[3] = {ray.ox, ray.oy, ray.oz};
  const double depth = depthOnFace(o[a], light[a], face);
  return std::isnan(depth) ? INFINITY : depth;
}

float missOfLight(const GrRay& ray, const glm::vec3& light) {
  const float reach =
      std::max({std::fabs(ray.ox), std::fabs(ray.oy), std::fabs(ray.oz)}) + ray.tmax;
  return std::sqrt(endToLightSquared(ray, light)) + endRoundingOf(reach);
}

LightRayBounds bundleLightRays(const UniformGrid& grid, const glm::vec3& light, const GrRay* rays,
                               size_t count, RayBundles& bundles, LightBundleScratch& scratch) {
  // Each ray's face and point on it, the faces' occupied windows, and how far the rays'
  // ends lie from the light.
  scratch.face_of.resize(count);
  scratch.uv.resize(2 * count);
  scratch.depth.resize(count);
  const int slices = parallelSliceCount();
  auto& thread_windows = scratch.thread_windows;
  thread_windows.assign(slices, std::array<FaceWindow, 6>{});
  std::vector<float> slice_miss(slices, 0.0f), slice_reach(slices, 0.0f),
      slice_length(slices, INFINITY);
  parallelSlices(slices, [&](int me, int n) {
    // Accumulated in the slice's own scan and stored once: the slices' slots share cache
    // lines. The lengths are kept squared and their roots taken once at the end (sqrt is
    // monotone, so the root of the largest square is the largest root): two roots a ray
    // were the pass's longest stall.
    LightRayScan scan;
    const auto [r0, r1] = sliceRange(count, me, n);
    scanLightRays(rays, r0, r1, light, scratch.face_of.data(), scratch.uv.data(),
                  scratch.depth.data(), scan);
    thread_windows[me] = scan.windows;
    // At least every ray's missOfLight: the root and the rounding term are each the
    // largest of the slice's (the L1 reach bounds missOfLight's |o|_inf + tmax), and a
    // rounded sum grows with its terms.
    slice_miss[me] = std::sqrt(scan.miss_squared) + endRoundingOf(scan.reach);
    slice_reach[me] = scan.reach;
    slice_length[me] = std::sqrt(scan.min_length_squared);
  });
  LightRayBounds bounds;
  const float miss = bounds.miss = *std::max_element(slice_miss.begin(), slice_miss.end());
  bounds.reach = *std::max_element(slice_reach.begin(), slice_reach.end());
  bounds.min_length = *std::min_element(slice_length.begin(), slice_length.end());
  // Each face's cells cover the window its rays occupy, about kLightRaysPerCell a cell.
  std::array<FaceWindow, 6>& faces = scratch.faces;
  faces = thread_windows[0];
  for (int t = 1; t < slices; ++t)
    for (int f = 0; f < 6; ++f) faces[f].merge(thread_windows[t][f]);
  int rows = 0;
  size_t cells = 0;
  for (FaceWindow& w : faces) {
    w.layout(rows, cells);
    rows += w.res;
    cells += size_t(w.res) * w.res;
  }
  scratch.cell_of.resize(count);
  parallelSlices(slices, [&](int me, int n) {
    const auto [r0, r1] = sliceRange(count, me, n);
    cellsOfLightRays(faces, scratch.face_of.data(), scratch.uv.data(), r0, r1,
                     scratch.cell_of.data());
  });

  // Bundle order: counting sort by cell, padded to whole packets. Stable and parallel:
  // each slice counts its own range of rays, and its rays of a cell follow the rays of
  // that cell from the slices before it.
  std::vector<int>& start = scratch.cell_start;
  start.assign(cells + 1, 0);
  bundles.ray_of.resize((count + GR_PACKET_LANES - 1) / GR_PACKET_LANES * GR_PACKET_LANES);
  scratch.thread_counts.resize(slices);
  scratch.thread_deepest.resize(slices);
  parallelSlices(slices, [&](int me, int n) {
    const auto [r0, r1] = sliceRange(count, me, n);
    std::vector<int>& mine = scratch.thread_counts[me];
    std::vector<double>& deepest = scratch.thread_deepest[me];
    mine.assign(cells, 0);
    deepest.assign(cells, -INFINITY);
    for (size_t r = r0; r < r1; ++r) {
      const int cell = scratch.cell_of[r];
      ++mine[cell];
      deepest[cell] = std::max(deepest[cell], scratch.depth[r]);
    }
  });
  // Each cell's deepest origin (light_bundles.h): the slices' maxima, in parallel by cell.
  std::vector<double>& deepest = scratch.thread_deepest[0];
  parallelFor(size_t(0), cells, [&](size_t c) {
    for (int t = 1; t < slices; ++t)
      deepest[c] = std::max(deepest[c], scratch.thread_deepest[t][c]);
  });
  int offset = 0;
  for (size_t c = 0; c < cells; ++c) {
    start[c] = offset;
    for (int t = 0; t < slices; ++t) {
      const int k = scratch.thread_counts[t][c];
      scratch.thread_counts[t][c] = offset;
      offset += k;
    }
  }
  start[cells] = offset;
  parallelSlices(slices, [&](int me, int n) {
    const auto [r0, r1] = sliceRange(count, me, n);
    std::vector<int>& mine = scratch.thread_counts[me];
    for (size_t r = r0; r < r1; ++r) bundles.ray_of[mine[scratch.cell_of[r]]++] = int(r);
  });
  std::fill(bundles.ray_of.begin() + count, bundles.ray_of.end(), -1);

  // Boxes are grown by the rays' largest miss of the light (rounding of the corners'
  // projections is covered by kLightFaceMargin, in cellRange).
  const float slack = kLightSlackFactor * miss;

  const int pes = grid.peCount();
  scratch.thread_runs.resize(slices);
  parallelSlices(slices, [&](int me, int count) {
    // A vector of the slice's own while it grows (false sharing, camera_bundles.cpp).
    auto runs = std::move(scratch.thread_runs[me]);
    runs.clear();
    // The cells [c0, c1) of row r, less those whose rays all start nearer to the light
    // than `near` (the box's nearest depth on this face): the runs of the others, where
    // a gap of fewer rays than a packet stays in the run (a task more would cost more).
    auto addRow = [&](int pe, int face, int r, int c0, int c1, double near) {
      const FaceWindow& fw = faces[face];
      const size_t row_cell = fw.first_cell + size_t(r) * fw.res;
      int first = -1, last = -1;  // the run being made, in bundle order
      for (int c = c0; c < c1;) {
        while (c < c1 && deepest[row_cell + c] < near) ++c;
        const int run_begin = c;
        while (c < c1 && !(deepest[row_cell + c] < near)) ++c;
        const int begin = start[row_cell + run_begin], end = start[row_cell + c];
        if (end == begin) continue;
        if (first >= 0 && begin - last >= GR_PACKET_LANES) {
          runs.push_back(LightBundleScratch::Run{pe, fw.first_row + r, first, last - first, face});
          first = -1;
        }
        if (first < 0) first = begin;
        last = end;
      }
      if (first >= 0)
        runs.push_back(LightBundleScratch::Run{pe, fw.first_row + r, first, last - first, face});
    };
    const auto [pe_begin, pe_end] = sliceRange(size_t(pes), me, count);
    for (int pe = int(pe_begin); pe < int(pe_end); ++pe) {
      glm::vec3 lo, hi;
      grid.hullOfPe(pe, lo, hi);
      lo -= slack;
      hi += slack;
      if (!std::isfinite(slack)) {  // rays that do not end anywhere near the light
        for (int face = 0; face < 6; ++face)
          for (int r = 0; r < faces[face].res; ++r)
            addRow(pe, face, r, 0, faces[face].res, -INFINITY);
        continue;
      }
      for (int face = 0; face < 6; ++face) {
        const FaceWindow& fw = faces[face];
        if (fw.res == 0) continue;
        const int a = face / 2, b = kOtherAxes[a][0], c = kOtherAxes[a][1];
        const float s = face % 2 ? -1.0f : 1.0f;
        // The part of the box in front of the face (depth s * (x_a - light_a) >= 0).
        // Corners at depth 0 project to infinity (IEEE x / 0), so a box beside or around
        // the light reaches the face's borders; 0 / 0 (a corner on the light's axis line)
        // says nothing and is left out, its neighbours span that side.
        glm::vec3 blo = lo, bhi = hi;
        if (s > 0.0f)
          blo[a] = std::max(blo[a], light[a]);
        else
          bhi[a] = std::min(bhi[a], light[a]);
        if (!(blo[a] <= bhi[a])) continue;
        // The box's nearest depth on this face (as originDepth's).
        const double near = depthOnFace(s > 0.0f ? blo[a] : bhi[a], light[a], face);
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
        // Cells, against rounding grown by kLightFaceMargin.
        int c0, c1, r0, r1;
        fw.cellRange(umin, umax, fw.u0, fw.su, c0, c1);
        fw.cellRange(vmin, vmax, fw.v0, fw.sv, r0, r1);
        for (int r = r0; r < r1; ++r) addRow(pe, face, r, c0, c1, near);
      }
    }
    scratch.thread_runs[me] = std::move(runs);
  });
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
  for (const auto& run : scratch.sorted) bundles.addRange(run.pe, run.first, run.count, run.face);
  for (int f = 0; f < 6; ++f) bounds.faces[f] = faces[f].res > 0;
  return bounds;
}

}  // namespace gridrt
