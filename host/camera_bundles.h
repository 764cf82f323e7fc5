// Primary rays of a pinhole camera as ray bundles (ray_bundles.h): the pixels of the
// view's window in square tiles of kTileSize x kTileSize (one 16-ray packet each), tiles
// row by row. A PE receives, for each tile row its voxel's screen footprint touches, the
// run of tiles the footprint covers; the kernel's slab test keeps the rays that really
// pierce the voxel, which are exactly the pairs of the rays' traversal lists.
#pragma once
#include <utility>
#include <vector>

#include "pinhole_view.h"
#include "ray_bundles.h"
#include "uniform_grid.h"

namespace gridrt {

constexpr int kTileSize = 4;  // kTileSize^2 == kBundleLanes

// One PE's tiles [tx0, tx1) of tile row ty.
struct TileRun {
  int pe, ty, tx0, tx1;
};

// Memory reused between calls.
struct CameraBundleScratch {
  std::vector<std::vector<TileRun>> thread_runs;  // each thread's runs
  std::vector<size_t> row_start;                  // counting sort by tile row
  std::vector<TileRun> sorted;
  std::vector<std::pair<float, int>> near_first;  // (distance to the eye, PE), PE order
  int layout_width = 0, layout_height = 0;        // the window RayBundles::ray_of is for
};

// near_first: tasks of nearer PEs first in every tile row (for the interrupt).
void bundleCameraRays(const UniformGrid& grid, const PinholeView& view, RayBundles& bundles,
                      bool near_first, CameraBundleScratch& scratch);

}  // namespace gridrt
