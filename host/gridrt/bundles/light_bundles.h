// Shadow rays towards one point (a point or spot light) as ray bundles (ray_bundles.h).
// Every such ray ends at the light, up to its origin offset and rounding, so seen from the
// light the rays form a pinhole image: their directions are binned on the six faces of a
// cube around the light (R x R cells a face) and sorted by face, cell row and cell. A PE
// receives, per cell row its voxel covers on a face, the run of rays in the covered
// cells; the kernel's slab test keeps the pairs of the traversal lists.
//
// A ray heads towards the light, so no point of it lies deeper (further from the light
// along its face's axis) than its origin: a PE receives, of the covered cells, only those
// holding a ray whose origin lies at least as deep as the PE's box, grown as above
// (shadow rays from the lit side of a model skip the PEs behind it: on the bunny 77 % of
// the lanes went to such PEs). Both depths are differences of floats taken in double,
// exact but where the two differ by more than 2^29 in magnitude, so no margin is added.
//
// Conservative by construction: a ray through a point q of a voxel whose end lies within m
// of the light points away from the light exactly as the direction from the light to a
// point within m of q does. So the voxel is grown by the largest such m (measured on the
// batch, with a bound on the rounding of the ends, times kLightSlackFactor) before it is
// projected; the projection of a box in front of the light is the hull of its corners',
// computed up to rounding (kLightFaceMargin); and the part of it that touches a plane
// through the light projects to the face borders.
#pragma once
#include <array>
#include <cmath>
#include <glm/glm.hpp>
#include <vector>

#include "gridrt_types.h"
#include "ray_bundles.h"
#include "uniform_grid.h"

namespace gridrt {

// Safety factor on the measured distance between the rays' ends and the light.
constexpr float kLightSlackFactor = 4.0f;
// The float end o + tmax * d of a ray is within this many FLT_EPSILON of (|o|inf + tmax)
// of its exact end (two roundings a coordinate, in 3D): added to each ray's measured
// miss, so that rays whose computed end is the light itself still get a slack.
constexpr float kLightEndRoundingEpsilons = 4.0f;
// A voxel's projected outline on a cube face is grown by this, relative (times 1 + |u|),
// on every side: a ray's face coordinate (one rounding) and a box corner's (three) are
// each within ~2e-7 relative of exact, and must not be split by a cell boundary.
constexpr float kLightFaceMargin = 1e-6f;

// The two axes spanning the faces of cube axis a: face 2a + s has coordinates
// (w[kOtherAxes[a][0]], w[kOtherAxes[a][1]]) / |w[a]| for a direction w from the light.
constexpr int kOtherAxes[3][2] = {{1, 2}, {2, 0}, {0, 1}};

// Rays a cube cell should hold on average.
constexpr float kLightRaysPerCell = 8.0f;

// The rectangle of one cube face its rays occupy (in face coordinates, [-1, 1]^2), cut
// into res x res cells: rays from a light towards a small object crowd a small part of
// one face, and the cells follow them there.
struct FaceWindow {
  float umin = INFINITY, umax = -INFINITY, vmin = INFINITY, vmax = -INFINITY;
  size_t count = 0;
  int res = 0;            // cells a side; 0 when no ray lies on this face
  int first_row = 0;      // the face's first row among all faces' rows
  size_t first_cell = 0;  // ... and first cell
  float u0 = 0.0f, v0 = 0.0f, su = 0.0f, sv = 0.0f;  // column = floor((u - u0) * su)

  void add(float u, float v);
  void merge(const FaceWindow& other);
  // Chooses res (about kLightRaysPerCell rays a cell) and places the face's cells.
  void layout(int first_row, size_t first_cell);
  size_t cellOf(float u, float v) const;  // of a ray on this face
  // The columns (rows) [c0, c1) that face coordinates [lo, hi] may touch, with [lo, hi]
  // grown by kLightFaceMargin.
  void cellRange(float lo, float hi, float origin, float scale, int& c0, int& c1) const;
};

struct LightBundleScratch {
  std::vector<int> face_of;                         // per ray
  std::vector<float> uv;                            // per ray, its point on the face
  std::vector<double> depth;                        // per ray, originDepth
  std::vector<std::vector<double>> thread_deepest;  // per thread and cell; [0]: the cells'
  std::array<FaceWindow, 6> faces;
  std::vector<int> cell_of;                     // per ray
  std::vector<int> cell_start;                  // counting sort by cell, then the run starts
  std::vector<std::vector<int>> thread_counts;  // per thread and cell (parallel sort)
  std::vector<std::array<FaceWindow, 6>> thread_windows;
  struct Run {
    int pe, row;  // row: the face's first row + cell row
    int first, count;
    int face;
  };
  std::vector<std::vector<Run>> thread_runs;
  std::vector<size_t> row_start;
  std::vector<Run> sorted;
};

// A bound on how far the exact end o + tmax * d of `ray` lies from `light`: the distance
// of its float end plus kLightEndRoundingEpsilons of its rounding (not finite for a ray
// without an end; the caller counts that as an infinite miss).
float missOfLight(const GrRay& ray, const glm::vec3& light);

// How far the origin of `ray` lies from `light` along the axis of cube face `face`, outwards
// (+infinity for NaN: such a ray is never left out).
double originDepth(const GrRay& ray, const glm::vec3& light, int face);

// What light culling (light_culling.h) needs to know of a batch of rays towards a light.
struct LightRayBounds {
  float miss = 0.0f;            // the largest missOfLight (infinite: a ray ends nowhere near it)
  float reach = 0.0f;           // the largest |o|_1 + |tmax| of a ray
  float min_length = INFINITY;  // the shortest |d| of a ray
  std::array<bool, 6> faces{};  // the cube faces that hold rays
};

// Each task's cull_set is the cube face of its rays.
LightRayBounds bundleLightRays(const UniformGrid& grid, const glm::vec3& light, const GrRay* rays,
                               size_t count, RayBundles& bundles, LightBundleScratch& scratch);

}  // namespace gridrt
