// The uniform grid of GridRT: the scene's box split into NX x NY x NZ equal voxels, each
// listing the triangles that really overlap it (separating-axis test, not bounding
// boxes). Every non-empty voxel is a processing element (PE), numbered in voxel order.
#pragma once
#include <glm/glm.hpp>
#include <vector>

#include "bounds.h"
#include "gridrt_types.h"
#include "uninitialized_vector.h"

namespace gridrt {

// Default lambda of the auto resolution R_i = d_i * cbrt(lambda * N / V): about lambda
// triangles per voxel volume; tune with --grid-density. Cleary & Wyvill and pbrt-v1
// recommend 3..5, but with packet culling a triangle a packet cannot hit costs a compare,
// so fewer, fuller voxels (fewer packets) win on the camera path; the list path (no
// culling) prefers finer voxels. Measured with settings alternated in one loop: going
// down from 4 to 0.5 and then to 0.1 made the bunny and teapot frames faster and left the
// default scene within noise; 0.05 makes the default scene slower (docs/history.md).
constexpr float kDefaultGridDensity = 0.1f;

// The grid box is the scene box grown by a margin, and every voxel is tested for overlap
// grown by the same margin, so a triangle within `margin` of a voxel is listed in it.
// That makes the grid conservative against float rounding of hit points: a hit computed
// just past a voxel boundary is still found by the voxel it is assigned to. What rounds
// are distances along a ray (Moeller-Trumbore's t from o - v0, the slabs' and the DDA's
// (plane - o) / d), so the scale is the longest way a ray can take through the grid: the
// diagonal of the box that holds the scene and the points rays start from (a far camera's
// rays are long). Coordinates do not enter: triangles are binned against the very float
// planes the DDA walks (min + k * cell in float), not their exact positions, which lie up to
// half an ulp of the coordinates away (Conformance.RandomRaysAroundAModelFarFromTheOrigin-
// MatchBrute loses hits at x = 10^4 when binned against the exact ones). ~170 float ulps of
// that diagonal. A scale of the coordinates (until 2026-12-03) gave a bunny 0.15 wide at x = 1,000
// a margin of 1 cm: leaves of hundreds of triangles, camera rays 6 times slower.
constexpr double kGridMarginRel = 1e-5;

// Upper bounds that keep the grid's memory sane whatever the density asks for.
constexpr int kMaxGridResolution = 512;
constexpr long long kMaxGridVoxels = 1 << 24;

// Uniform: the uniform grid. Adaptive: the adaptive structure. WhereNeeded (the command
// line's --grid auto): the adaptive structure when a voxel of the uniform grid holds more
// than max_leaf_triangles triangles, else the uniform grid itself.
enum class GridStructure { Uniform, Adaptive, WhereNeeded };

struct GridSettings {
  bool automatic = true;  // derive the resolution from N and the box's shape
  float density = kDefaultGridDensity;
  glm::ivec3 dims{1, 1, 1};            // used when !automatic
  double margin_rel = kGridMarginRel;  // tests set 0 to show what the margin prevents
  // With automatic: which structure buildGrid makes (adaptive_grid.h).
  GridStructure structure = GridStructure::Uniform;
  // The adaptive structure splits a leaf holding more triangles than this (adaptive_grid.h:
  // kMaxLeafTriangles; tests set fewer to reach its deeper levels on small scenes).
  int max_leaf_triangles = 256;
  // Where rays start outside the scene's box (the camera: primaryRayOrigins). A hit's
  // rounding grows with its distance from the ray's origin, so the margin's scale is the
  // diagonal of the box holding the scene and these points. Empty: the scene's only.
  Bounds ray_origins;
};

// A grid below a cell of the adaptive structure (adaptive_grid.h): dims[a] cells on axis
// a between the planes planes[plane_begin[a] .. plane_begin[a] + dims[a]] (increasing; the
// first and last are the parent cell's faces, the same floats), cells x fastest from
// cell_begin, each coded as in AdaptiveCells::top.
struct GridNode {
  int dims[3];
  int plane_begin[3];
  int cell_begin;
};

// The adaptive structure's cells (adaptive_grid.h); empty for a uniform grid. A cell's code:
// -1 empty, >= 0 the PE it belongs to (a leaf, or part of a merged leaf), <= -2 the grid
// node -(code + 2) below it.
struct AdaptiveCells {
  std::vector<int> top;  // per voxel of the top grid (GrGridInfo), x fastest
  std::vector<GridNode> nodes;
  std::vector<int> cells;
  std::vector<float> planes;
  int depth = 0;  // levels below the top grid
  bool empty() const { return top.empty(); }
};

struct UniformGrid {
  GrGridInfo info{};
  double margin = 0.0;
  std::vector<int> pe_of_voxel;   // per voxel (x fastest), -1 if empty
  std::vector<int> voxel_of_pe;   // per PE, its linear voxel index
  std::vector<int> pe_tri_begin;  // per PE + 1: CSR offsets into pe_triangles
  // Per PE, its triangles in increasing global index (sized without zeroing: the build
  // writes every element).
  UninitializedVector<GrTriangle> pe_triangles;
  size_t triangle_count = 0;
  // Per PE its box, lo x, y, z then hi x, y, z: for a uniform grid the voxel with the
  // 3D-DDA's plane arithmetic (min + k * cell, in float), for the adaptive structure its
  // leaf (faces on the planes of the grids above it). The kernels take it from here.
  std::vector<float> pe_box;
  // Per PE its box cut down to its triangles' bounds grown by the margin (pe_hulls.h), as
  // pe_box; the ray bundles read it.
  std::vector<float> pe_hull;
  // The adaptive structure's cells; then pe_of_voxel and voxel_of_pe are empty.
  AdaptiveCells adaptive;

  int peCount() const { return pe_tri_begin.empty() ? 0 : int(pe_tri_begin.size()) - 1; }
  // The top grid's voxels.
  size_t voxelCount() const { return adaptive.empty() ? pe_of_voxel.size() : adaptive.top.size(); }
  int triangleCountOfPe(int pe) const { return pe_tri_begin[pe + 1] - pe_tri_begin[pe]; }
  size_t memoryBytes() const;
  glm::ivec3 voxelCoords(int linear) const;
  // The box of PE `pe`'s voxel with the 3D-DDA's plane arithmetic (min + k * cell, in
  // float), so its faces are bit for bit the planes the traversal uses.
  void voxelBoxOfPe(int pe, glm::vec3& lo, glm::vec3& hi) const;
  // PE `pe`'s hull (pe_hull; its box where the grid has none).
  void hullOfPe(int pe, glm::vec3& lo, glm::vec3& hi) const;
};

// The voxels of a uniform grid and the triangles each lists as positions in the input: the
// first step of buildUniformGrid, and the top level the adaptive structure starts from
// without copying triangles.
struct UniformBins {
  GrGridInfo info{};
  double margin = 0.0;
  std::vector<int> pe_of_voxel;   // as UniformGrid's
  std::vector<int> voxel_of_pe;   // as UniformGrid's
  std::vector<int> pe_tri_begin;  // per PE + 1: CSR offsets into positions
  std::vector<int> positions;     // per PE, its triangles' positions in the input, increasing
  int peCount() const { return pe_tri_begin.empty() ? 0 : int(pe_tri_begin.size()) - 1; }
  int triangleCountOfPe(int pe) const { return pe_tri_begin[pe + 1] - pe_tri_begin[pe]; }
};

// Voxel `linear`'s coordinates (x fastest) in a grid of info's dimensions.
glm::ivec3 voxelCoordsIn(const GrGridInfo& info, int linear);

// One axis of a grid's cells as both grids' binning searches them: cell i from planes[i]
// to planes[i + 1] (increasing; the float planes the walks use), each grown by m. It keeps
// a pointer to the planes, which must outlive it.
class AxisCells {
 public:
  AxisCells(const std::vector<float>& planes, double m);
  // The cells [first, last] whose grown extent may meet [lo, hi]: widened by a billionth
  // of the mean cell against double rounding (the exact overlap test decides), clamped to
  // the cells.
  void range(double lo, double hi, int& first, int& last) const;

 private:
  const float* planes_;
  int cells_;
  double p0_, cells_per_unit_, m_, slack_;
};

// R_i = d_i * cbrt(density * N / V), each at least 1, capped by the limits above.
// Flat or empty extents are floored at 1e-3 of the largest so V is never 0.
glm::ivec3 autoGridResolution(const Bounds& bounds, size_t triangle_count, float density);

// The uniform grid over `triangles` (global order), on all cores, in two steps:
// binUniformGrid sorts the triangles' positions into the voxels; uniformGridOf copies the
// triangles in and makes the PEs' boxes and hulls.
UniformBins binUniformGrid(const std::vector<GrTriangle>& triangles, const Bounds& bounds,
                           const GridSettings& settings);
UniformGrid uniformGridOf(UniformBins&& bins, const std::vector<GrTriangle>& triangles);
UniformGrid buildUniformGrid(const std::vector<GrTriangle>& triangles, const Bounds& bounds,
                             const GridSettings& settings);

}  // namespace gridrt
