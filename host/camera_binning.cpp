#include "camera_binning.h"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <glm/gtc/matrix_transform.hpp>

namespace gridrt {

PinholeView PinholeView::of(const Camera& camera, int width, int height, PixelWindow window) {
  PinholeView v;
  v.world_to_camera = glm::inverse(camera.world);
  v.tan_half = std::tan(camera.yfov * 0.5f);
  v.aspect = camera.aspect > 0.0f ? camera.aspect : float(width) / float(height);
  v.width = width;
  v.height = height;
  v.window = window.whole() ? PixelWindow{0, 0, width, height} : window;
  return v;
}

const GrPeEntry* CameraBins::entriesOf(const GrPeTask& task) const {
  for (size_t t = 0; t < thread_offset.size(); ++t)
    if (size_t(task.slot_base) == thread_offset[t] && !thread_entries[t].empty() &&
        size_t(task.first_entry) - thread_offset[t] < thread_entries[t].size())
      return thread_entries[t].data() + (task.first_entry - task.slot_base);
  return nullptr;
}

namespace {

// Pixels whose centre rays may pierce the box: the bounding rectangle of its projected
// corners, one pixel wider each side against rounding; the whole window when a corner
// lies at or behind the camera plane.
PixelWindow footprint(const PinholeView& v, const glm::vec3& lo, const glm::vec3& hi) {
  float imin = 1e30f, imax = -1e30f, jmin = 1e30f, jmax = -1e30f;
  for (int c = 0; c < 8; ++c) {
    glm::vec3 corner(c & 1 ? hi.x : lo.x, c & 2 ? hi.y : lo.y, c & 4 ? hi.z : lo.z);
    glm::vec4 p = v.world_to_camera * glm::vec4(corner, 1.0f);
    if (!(p.z < 0.0f)) return v.window;
    float x = p.x / (-p.z) / (v.tan_half * v.aspect), y = p.y / (-p.z) / v.tan_half;
    float i = (x + 1.0f) * 0.5f * float(v.width) - 0.5f;
    float j = (1.0f - y) * 0.5f * float(v.height) - 0.5f;
    imin = std::min(imin, i);
    imax = std::max(imax, i);
    jmin = std::min(jmin, j);
    jmax = std::max(jmax, j);
  }
  PixelWindow f;
  f.x0 = std::max(v.window.x0, int(std::floor(imin)) - 1);
  f.x1 = std::min(v.window.x1, int(std::ceil(imax)) + 2);
  f.y0 = std::max(v.window.y0, int(std::floor(jmin)) - 1);
  f.y1 = std::min(v.window.y1, int(std::ceil(jmax)) + 2);
  return f;
}

// The ray's interval inside [lo, hi] on one axis, with the 3D-DDA's exact arithmetic
// ((plane - o) * (1/d)); a zero direction is inside or outside the slab for every t.
inline void slab(float o, float d, float inv, float lo, float hi, float& t0, float& t1) {
  if (d == 0.0f) {
    if (o < lo || o > hi) t0 = INFINITY;
    return;
  }
  float a = (lo - o) * inv, b = (hi - o) * inv;
  t0 = std::max(t0, std::min(a, b));
  t1 = std::min(t1, std::max(a, b));
}

}  // namespace

void binCameraRaysByPe(const UniformGrid& grid, const PinholeView& view, const GrRay* rays,
                       size_t count, int task_rays, CameraBins& bins) {
  const GrGridInfo& g = grid.info;
  const int pes = grid.peCount();
  const int threads = omp_get_max_threads();
  const int ww = view.window.width();
  bins.inv_dir.resize(3 * count);
  bins.thread_entries.resize(threads);
  bins.thread_tasks.resize(threads);
  bins.pairs_per_pe.assign(pes, 0);
#pragma omp parallel num_threads(threads)
  {
    const int me = omp_get_thread_num();
    auto& out = bins.thread_entries[me];
    auto& tasks = bins.thread_tasks[me];
    out.clear();
    tasks.clear();
#pragma omp for schedule(static)
    for (long long r = 0; r < (long long)count; ++r)
      for (int a = 0; a < 3; ++a) {
        float d = (&rays[r].dx)[a];
        bins.inv_dir[3 * r + a] = d != 0.0f ? 1.0f / d : 0.0f;
      }
#pragma omp for schedule(dynamic, 8)
    for (int pe = 0; pe < pes; ++pe) {
      glm::ivec3 v = grid.voxelCoords(grid.voxel_of_pe[pe]);
      // The voxel's planes exactly as the DDA computes them: min + k * cell.
      glm::vec3 lo(g.minx + float(v.x) * g.cellx, g.miny + float(v.y) * g.celly,
                   g.minz + float(v.z) * g.cellz);
      glm::vec3 hi(g.minx + float(v.x + 1) * g.cellx, g.miny + float(v.y + 1) * g.celly,
                   g.minz + float(v.z + 1) * g.cellz);
      PixelWindow f = footprint(view, lo, hi);
      int first = int(out.size());
      if (f.x1 <= f.x0 || f.y1 <= f.y0) {
        bins.pairs_per_pe[pe] = 0;
        continue;
      }
      // Branch-free compaction: every pixel writes its pair, only piercing ones advance.
      out.resize(first + size_t(f.width()) * f.height());
      GrPeEntry* next = out.data() + first;
      for (int j = f.y0; j < f.y1; ++j) {
        int r = (j - view.window.y0) * ww + (f.x0 - view.window.x0);
        for (int i = f.x0; i < f.x1; ++i, ++r) {
          const GrRay& ray = rays[r];
          const float* inv = &bins.inv_dir[3 * size_t(r)];
          float t0 = ray.tmin, t1 = ray.tmax;
          slab(ray.ox, ray.dx, inv[0], lo.x, hi.x, t0, t1);
          slab(ray.oy, ray.dy, inv[1], lo.y, hi.y, t0, t1);
          slab(ray.oz, ray.dz, inv[2], lo.z, hi.z, t0, t1);
          *next = GrPeEntry{r, int(next - out.data()), t0, t1};
          next += t0 <= t1;
        }
      }
      out.resize(next - out.data());
      int n = int(out.size()) - first;
      bins.pairs_per_pe[pe] = n;
      for (int k = 0; k < n; k += task_rays)
        tasks.push_back(GrPeTask{pe, first + k, std::min(task_rays, n - k), 0});
    }
  }
  // Offsets of the threads' bins in the device buffer; tasks point into it.
  bins.thread_offset.assign(threads, 0);
  bins.tasks.clear();
  size_t offset = 0;
  for (int t = 0; t < threads; ++t) {
    bins.thread_offset[t] = offset;
    for (GrPeTask task : bins.thread_tasks[t]) {
      task.first_entry += int(offset);
      task.slot_base = int(offset);
      bins.tasks.push_back(task);
    }
    offset += bins.thread_entries[t].size();
  }
  bins.entry_count = offset;
}

}  // namespace gridrt
