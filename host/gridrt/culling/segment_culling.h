// Segment culling for rays with their own origins (reflection, refraction and shadow rays):
// the PE kernel skips a triangle for a 16-ray packet when the triangle lies further from
// every lane's segment inside the voxel than the ray/triangle test's rounding can reach,
// so the hits stay bit-identical to brute force.
//
// Where the test reports a hit at t for a ray (o, d), the point o + t d of the ray lies
// within M = E * K * (|o|_1 + |t| + |v0|_1 + |e1| + |e2|) of the triangle, with
// K = |e1| |e2| / |d . (e1 x e2)| (1 / (sin of the triangle's angle at v0 * cos of the
// incidence): the conditioning of the test's three Cramer quotients) and E a few units of
// rounding. The kernel projects the triangle and the lanes' segments [t_lo, t_hi] (t_lo,
// t_hi: the voxel's interval, clipped to the ray's) onto two axes across the packet's mean
// direction, where coherent segments are short, and skips the triangle when the two boxes
// are more than M apart, with K bounded over the packet's direction box. The per-triangle
// part is precomputed here, once per grid: the planes of gridrt_types.h (GR_SEG_*).
#pragma once
#include <cstddef>
#include <string>
#include <vector>

#include "gridrt_types.h"

namespace gridrt {

// E in units of 2^-24: the rounding analysis of Moeller-Trumbore gives about 3 * 6 (three
// quotients, each with a numerator and a determinant of a few roundings), and
// SegmentCulling.MarginCoversTheTestsRounding finds 7 (MT) and 23 (watertight) of ~400k
// hits outside with 0.5, none with 1;
// 64 is margin.
constexpr double kSegmentCullErrorFactor = 64.0;
// A triangle is never culled for a packet whose K may exceed this (a lane nearly grazing
// its plane, or a sliver): the first-order rounding bound needs E * K small.
constexpr double kSegmentCullMaxConditioning = 1024.0;
// PEs with fewer triangles skip the packet's summary, which costs about what testing a
// few triangles does.
constexpr int kSegmentCullMinTriangles = 16;
// The padding after each plane: the kernel reads a float16 of triangles at a time.
constexpr size_t kSegmentCullPlanePadding = GR_PACKET_LANES;

// The planes for `triangles` (the PE triangles, MT edges or watertight vertices), each
// stride = triangles + kSegmentCullPlanePadding floats long.
void computeSegmentCullPlanes(const std::vector<GrTriangle>& triangles, std::vector<float>& planes);
// The same planes written to `planes` (GR_SEG_PLANES * (count + kSegmentCullPlanePadding)
// floats, the padding zeroed), on all cores: straight into a mapped device buffer.
void writeSegmentCullPlanes(const GrTriangle* triangles, size_t count, float* planes);

// The margin M for one ray (o, d) whose hit may lie at parameters up to |t_hi|, computed
// from the planes of triangle `index` as the kernel does, in double; +infinity where the
// kernel never culls (K above kSegmentCullMaxConditioning). For tests.
double segmentCullMargin(const std::vector<float>& planes, size_t index, const GrRay& ray,
                         float t_hi, double error_factor = kSegmentCullErrorFactor);

// The kernels' build options that carry the constants above.
std::string segmentCullDefines();

}  // namespace gridrt
