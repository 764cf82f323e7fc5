// Camera bundles (host/gridrt/bundles/camera_bundles.h): a PE must receive every pixel whose float
// centre ray the kernel's slab test lets into its voxel, or the camera path loses hits the
// traversal lists would find. The hard cases are views whose pixels are finer than the
// rays' rounding: narrow fields of view on large images, and boxes far from the world
// origin (where a float projection of their corners cancels).
#include "camera_bundles.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <set>

#include "camera_rays.h"
#include "prepared_triangles.h"
#include "uniform_grid.h"

namespace gridrt {
namespace {

// The slab test of kernels/gridrt_bundles.cl (gr_slab16) on one float ray over [0, inf):
// the same operations in the same order (the host, like the kernels, never contracts).
bool slabPierces(const GrRay& r, const glm::vec3& lo, const glm::vec3& hi) {
  const float o[3] = {r.ox, r.oy, r.oz}, d[3] = {r.dx, r.dy, r.dz};
  float t0 = r.tmin, t1 = r.tmax;
  for (int a = 0; a < 3; ++a) {
    const float inv = 1.0f / d[a];
    const float ta = (lo[a] - o[a]) * inv, tb = (hi[a] - o[a]) * inv;
    if (d[a] == 0.0f) {
      if (o[a] < lo[a] || o[a] > hi[a]) t0 = INFINITY;
    } else {
      t0 = std::fmax(t0, std::fmin(ta, tb));
      t1 = std::fmin(t1, std::fmax(ta, tb));
    }
  }
  return t0 <= t1;
}

// A grid of dims over [-1, 1]^3 + shift with every voxel holding a triangle.
UniformGrid filledGrid(const glm::vec3& shift, glm::ivec3 dims) {
  std::vector<GrTriangle> tris;
  for (int z = 0; z < dims.z; ++z)
    for (int y = 0; y < dims.y; ++y)
      for (int x = 0; x < dims.x; ++x) {
        const glm::vec3 c =
            shift + glm::vec3(-1.0f) + 2.0f * (glm::vec3(x, y, z) + 0.5f) / glm::vec3(dims);
        const glm::vec3 v[3] = {c, c + glm::vec3(0.05f, 0, 0), c + glm::vec3(0, 0.05f, 0.02f)};
        tris.push_back(prepareTriangle(v, int(tris.size())));
      }
  Bounds b;
  b.grow(shift - glm::vec3(1.0f));
  b.grow(shift + glm::vec3(1.0f));
  GridSettings s;
  s.automatic = false;
  s.dims = dims;
  UniformGrid grid = buildUniformGrid(tris, b, s);
  // The bundles see the PEs' hulls, here cut down to the small triangles; the views aim
  // where whole boxes meet, so the hulls are the boxes (the outline code is the same).
  grid.pe_hull = grid.pe_box;
  return grid;
}

struct Coverage {
  size_t pierced = 0;  // (pixel, PE) pairs the slab test lets through
  size_t missed = 0;   // ... whose pixel the PE's tile runs do not hold
};

// Views aimed at grid vertices (where voxels meet, so the window straddles boundaries)
// from random directions and distances, with random fields of view and image sizes.
Coverage checkRandomViews(float shift_scale, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  std::normal_distribution<float> gauss;
  const glm::ivec3 dims(4, 3, 5);
  Coverage c;
  for (int view_index = 0; view_index < 60; ++view_index) {
    glm::vec3 axis(gauss(rng), gauss(rng), gauss(rng));
    const glm::vec3 shift = shift_scale * glm::normalize(axis);
    const UniformGrid grid = filledGrid(shift, dims);
    const GrGridInfo& g = grid.info;
    const glm::ivec3 vertex(1 + int(unit(rng) * (dims.x - 1)), 1 + int(unit(rng) * (dims.y - 1)),
                            1 + int(unit(rng) * (dims.z - 1)));
    const glm::vec3 target(g.minx + float(vertex.x) * g.cellx, g.miny + float(vertex.y) * g.celly,
                           g.minz + float(vertex.z) * g.cellz);
    glm::vec3 towards_eye(gauss(rng), gauss(rng), gauss(rng));
    const float distance = 3.0f * std::pow(1000.0f, unit(rng));
    const float fov = glm::radians(0.01f * std::pow(17000.0f, unit(rng)));  // 0.01 .. 170 degrees
    const int height = view_index % 3 == 0 ? 480 : view_index % 3 == 1 ? 4000 : 15000;
    const int width = height * 4 / 3;
    const Camera camera =
        lookAtCamera(target + glm::normalize(towards_eye) * distance, target, fov);
    const PixelWindow window{width / 2 - 24, height / 2 - 24, width / 2 + 24, height / 2 + 24};
    const PinholeView view = PinholeView::of(camera, width, height, window);
    RayBundles bundles;
    CameraBundleScratch scratch;
    bundleCameraRays(grid, view, bundles, false, scratch);
    std::set<std::pair<int, int>> received;  // (PE, ray)
    for (const GrBundleTask& task : bundles.tasks)
      for (int slot = task.first_ray; slot < task.first_ray + task.ray_count; ++slot)
        if (bundles.ray_of[slot] >= 0) received.insert({task.pe, bundles.ray_of[slot]});
    const CameraRayGenerator rays(camera, width, height);
    for (int y = window.y0; y < window.y1; ++y)
      for (int x = window.x0; x < window.x1; ++x) {
        const GrRay ray = rays(x, y, 0.5f, 0.5f);
        const int r = (y - window.y0) * window.width() + (x - window.x0);
        for (int pe = 0; pe < grid.peCount(); ++pe) {
          glm::vec3 lo, hi;
          grid.hullOfPe(pe, lo, hi);  // the box the bundle kernel's slab test reads
          if (!slabPierces(ray, lo, hi)) continue;
          ++c.pierced;
          if (!received.count({pe, r})) {
            if (c.missed == 0)
              ADD_FAILURE() << "pixel (" << x << ", " << y << ") of " << width << "x" << height
                            << " at fov " << glm::degrees(fov) << " deg, " << distance
                            << " from a box shifted by " << shift_scale << ": PE " << pe
                            << " pierced but not sent";
            ++c.missed;
          }
        }
      }
  }
  return c;
}

// Without kCameraOutlineEpsilons (0) pixels at the narrowest views are lost; with the old
// float projection a box 1e3..1e4 from the origin lost hundreds of pixels a view.
TEST(CameraBundles, EveryPixelTheSlabTestLetsIntoAVoxelReachesItsPe) {
  for (float shift : {0.0f, 1e3f, 1e4f}) {
    const Coverage c = checkRandomViews(shift, 17 + uint32_t(shift));
    EXPECT_GT(c.pierced, 60u * 48 * 48) << "shift " << shift;  // every view meets several voxels
    EXPECT_EQ(c.missed, 0u) << "shift " << shift << " of " << c.pierced << " pierced pairs";
  }
}

}  // namespace
}  // namespace gridrt
