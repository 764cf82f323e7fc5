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

constexpr int kTileSize = 4;  // kTileSize^2 == GR_PACKET_LANES

// One PE's tiles [tx0, tx1) of tile row ty.
struct TileRun {
  int pe, ty, tx0, tx1;
};

// Memory reused between calls.
struct CameraBundleScratch {
  std::vector<std::vector<TileRun>> thread_runs;  // each thread's runs
  // (distance to the eye, slot in pe_runs) of the PEs in view, nearest first when asked
  std::vector<std::pair<float, int>> near_first;
  std::vector<std::pair<float, int>> sort_scratch;                 // the radix sort's second buffer
  std::vector<std::pair<const TileRun*, const TileRun*>> pe_runs;  // each such PE's runs
  int layout_width = 0, layout_height = 0;  // the window RayBundles::ray_of is for
};

// How far (in pixels) a voxel's projected outline is grown on every side, so that every
// pixel whose float centre ray the kernel's slab test lets into the voxel is in a tile of
// its footprint. The outline is exact (double); the rays are not: a centre ray's
// direction lies a dozen roundings of unit-size values from its pixel's exact direction,
// its pixel coordinate a few roundings of the image size from the pixel's, and the slab
// test passes rays a few roundings (relative to t) outside the box, an angle of a few
// epsilons from the eye. Angles become pixels at the image corner's gnomonic stretch
// (1 + tan^2 (aspect^2 + 1)) times the pixels per radian at the centre. Budget, in float
// epsilons (2^-24) of both: 64, about four times the sum
// (tests/gridrt/bundles/camera_bundles_test.cpp).
constexpr double kCameraOutlineEpsilons = 64.0;
double cameraOutlineMargin(const PinholeView& view);

// near_first: the tasks of nearer PEs first (for the interrupt).
void bundleCameraRays(const UniformGrid& grid, const PinholeView& view, RayBundles& bundles,
                      bool near_first, CameraBundleScratch& scratch);

}  // namespace gridrt
