// Shadow rays towards one point (a point or spot light) as ray bundles (ray_bundles.h).
// Every such ray ends at the light, up to its origin offset and rounding, so seen from the
// light the rays form a pinhole image: their directions are binned on the six faces of a
// cube around the light (R x R cells a face) and sorted by face, cell row and cell. A PE
// receives, per cell row its voxel covers on a face, the run of rays in the covered
// cells; the kernel's slab test keeps the pairs of the traversal lists.
//
// Conservative by construction: the voxel is grown by the largest distance between a
// ray's end and the light (measured on the batch: the origin offset plus rounding, times
// kLightSlackFactor) before it is projected, its projection is grown by one cell, and
// the part of it that touches a plane through the light projects to the face borders.
#pragma once
#include <glm/glm.hpp>
#include <vector>

#include "gridrt_types.h"
#include "ray_bundles.h"
#include "uniform_grid.h"

namespace gridrt {

// Safety factor on the measured distance between the rays' ends and the light.
constexpr float kLightSlackFactor = 4.0f;
// Cells added on every side of a projected box: the projection's rounding (a few ulps
// of the face coordinates) is far below a cell. No test isolates it (the slack covers).
constexpr int kLightCellMargin = 1;

struct LightBundleScratch {
  std::vector<int> cell_of;     // per ray
  std::vector<int> cell_start;  // counting sort by cell, then the run starts
  struct Run {
    int pe, row;  // row: face * R + cell row
    int first, count;
  };
  std::vector<std::vector<Run>> thread_runs;
  std::vector<size_t> row_start;
  std::vector<Run> sorted;
};

// Cells per cube face edge for `count` rays: about eight rays per cell on two faces.
int lightCubeResolution(size_t count);

void bundleLightRays(const UniformGrid& grid, const glm::vec3& light, const GrRay* rays,
                     size_t count, RayBundles& bundles, LightBundleScratch& scratch);

}  // namespace gridrt
