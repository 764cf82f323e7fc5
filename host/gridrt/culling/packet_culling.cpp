#include "packet_culling.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

#include "outward_rounding.h"
#include "parallel_loops.h"
#include "prefault.h"
#include "prepared_triangles.h"
#include "segment_culling.h"

namespace gridrt {

namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();
constexpr CullBox kUnculled{-kInf, kInf, -kInf, kInf};

glm::dvec3 forwardOf(const GrCullFrame& f) { return {f.fx, f.fy, f.fz}; }
glm::dvec3 rightOf(const GrCullFrame& f) { return {f.rx, f.ry, f.rz}; }
glm::dvec3 upOf(const GrCullFrame& f) { return {f.ux, f.uy, f.uz}; }

// Triangles a block of boxesOfBlock: its staging arrays stay in the first-level cache.
constexpr int kCullBlock = 256;

// The boxes of the `count` <= kCullBlock triangles from `triangles` on, as planes (the
// boxes' amin, amax, bmin, bmax from amin[0], amax[0], ... on). Two loops: the vertices
// staged by coordinate, then all of the arithmetic and the outward rounding in one loop
// that vectorises (no branch: every lane computes everything and the triangles that cannot
// be culled are chosen by a select; no library call: the outward rounding is inline). One
// triangle at a time with early returns, the boxes and their planes took 79 ms of the row
// of 16 bunnies' first frame (1.56 M triangles of PEs, 2 cores); this takes 14.5.
//
// With `towards` (rays that end at o instead of starting there: light_culling.h) each box
// is grown further by what the rays' own origins add (TowardsOrigin); a triangle nearly
// edge-on to o, or whose test may be ill-conditioned for those rays, stays unculled.
// kTowards is a template parameter: a branch on it inside the loop kept the camera's boxes
// from vectorising (the row of 16 bunnies' first camera frame 33 -> 69 ms).
template <bool kTowards>
void boxesOfBlock(const GrCullFrame& frame, const glm::dvec3& o, const GrTriangle* triangles,
                  int count, double error_factor, const TowardsOrigin& towards, float* amin_out,
                  float* amax_out, float* bmin_out, float* bmax_out) {
  const double miss = towards.miss, ray_reach = towards.ray_reach, min_length = towards.min_length,
               seg_error = towards.segment_error_factor * 0x1p-24;
  // The vertices relative to the origin, by coordinate.
  double wx[3][kCullBlock], wy[3][kCullBlock], wz[3][kCullBlock];
  for (int k = 0; k < count; ++k) {
    glm::dvec3 v[3];
    triangleVertices(triangles[k], v);
    for (int i = 0; i < 3; ++i) {
      wx[i][k] = v[i].x - o.x;
      wy[i][k] = v[i].y - o.y;
      wz[i][k] = v[i].z - o.z;
    }
  }
  const glm::dvec3 f = forwardOf(frame), r = rightOf(frame), u = upOf(frame);
#pragma omp simd
  for (int k = 0; k < count; ++k) {
    // One square root (the farthest vertex) and a division a vertex: this runs for every
    // triangle of every PE whenever the camera moves.
    double far2 = 0.0;
    for (int i = 0; i < 3; ++i) {
      const double d2 = wx[i][k] * wx[i][k] + wy[i][k] * wy[i][k] + wz[i][k] * wz[i][k];
      far2 = far2 > d2 ? far2 : d2;
    }
    const double far = std::sqrt(far2);
    double a[3], b[3], z_min = std::numeric_limits<double>::infinity();
    bool in_front = true;
    for (int i = 0; i < 3; ++i) {
      const double z = wx[i][k] * f.x + wy[i][k] * f.y + wz[i][k] * f.z;
      in_front = in_front && z > kCullMinDepth * far;
      z_min = z_min < z ? z_min : z;
      const double inv_z = 1.0 / z;  // a double rounding more: nothing beside the margin
      a[i] = (wx[i][k] * r.x + wy[i][k] * r.y + wz[i][k] * r.z) * inv_z;
      b[i] = (wx[i][k] * u.x + wy[i][k] * u.y + wz[i][k] * u.z) * inv_z;
    }
    // Edges and normal from the relative vertices (the same differences as of the
    // vertices, exact in double for float vertices near each other, else within its
    // rounding, which the margin covers).
    const double e1x = wx[1][k] - wx[0][k], e1y = wy[1][k] - wy[0][k], e1z = wz[1][k] - wz[0][k];
    const double e2x = wx[2][k] - wx[0][k], e2y = wy[2][k] - wy[0][k], e2z = wz[2][k] - wz[0][k];
    const double e3x = wx[2][k] - wx[1][k], e3y = wy[2][k] - wy[1][k], e3z = wz[2][k] - wz[1][k];
    const double nx = e1y * e2z - e1z * e2y, ny = e1z * e2x - e1x * e2z, nz = e1x * e2y - e1y * e2x;
    const double l1 = e1x * e1x + e1y * e1y + e1z * e1z, l2 = e2x * e2x + e2y * e2y + e2z * e2z,
                 l3 = e3x * e3x + e3y * e3y + e3z * e3z;
    const double edge2 = l1 > l2 ? (l1 > l3 ? l1 : l3) : (l2 > l3 ? l2 : l3);
    const double incidence = std::abs(nx * wx[0][k] + ny * wy[0][k] + nz * wz[0][k]);
    const double kappa = edge2 * far / incidence;
    double spread = 1.0, amin = a[0], amax = a[0], bmin = b[0], bmax = b[0];
    for (int i = 0; i < 3; ++i) {
      const double s = 1.0 + std::abs(a[i]) + std::abs(b[i]);
      spread = spread > s ? spread : s;
      amin = amin < a[i] ? amin : a[i];
      amax = amax > a[i] ? amax : a[i];
      bmin = bmin < b[i] ? bmin : b[i];
      bmax = bmax > b[i] ? bmax : b[i];
    }
    double margin = error_factor * 0x1p-24 * kappa * (far / z_min) * spread * spread;
    // Rays towards o (TowardsOrigin): a ray whose test reports a hit passes within
    // delta = E K (reach of the ray + of the triangle) of a point Y of the triangle
    // (segment_culling.h), K = |e1| |e2| / |d . n| with |d . n| >= |d| |n| cos / 2, where
    // cos = (distance of o from the triangle's plane) / far bounds the cosine between n and
    // the direction from any Y to o, and the ray's direction strays from it by at most
    // g / (z_min - g), g = miss + delta, which must stay below cos / 2. Seen from o, Y then
    // lies within g of the ray's line, which moves its (a, b) off the lane's by at most
    // g * spread / (z_min - g).
    bool towards_ok = true;
    if constexpr (kTowards) {
      const double n_length = std::sqrt(nx * nx + ny * ny + nz * nz);
      const double cos_plane = incidence / (n_length * far);
      const double conditioning = std::sqrt(l1 * l2) / (min_length * n_length * 0.5 * cos_plane);
      const double v0_reach =
          std::abs(wx[0][k] + o.x) + std::abs(wy[0][k] + o.y) + std::abs(wz[0][k] + o.z);
      const double triangle_reach = v0_reach + std::sqrt(l1) + std::sqrt(l2);
      const double g = miss + seg_error * conditioning * (ray_reach + triangle_reach);
      towards_ok = conditioning <= kSegmentCullMaxConditioning && z_min > g &&
                   g / (z_min - g) <= 0.5 * cos_plane;
      margin += g * spread / (z_min - g);
    }
    // Not in front, or edge-on or degenerate (a margin of 1 or more, infinite or NaN).
    const bool cullable = in_front && towards_ok && margin < 1.0;
    amin_out[k] = cullable ? floatBelow(amin - margin) : kUnculled.amin;
    amax_out[k] = cullable ? floatAbove(amax + margin) : kUnculled.amax;
    bmin_out[k] = cullable ? floatBelow(bmin - margin) : kUnculled.bmin;
    bmax_out[k] = cullable ? floatAbove(bmax + margin) : kUnculled.bmax;
  }
}

// boxesOfBlock over all `triangles`, in parallel, into planes of `stride` floats from
// `planes` on.
void boxPlanes(const GrCullFrame& frame, const glm::vec3& origin, const GrTriangle* triangles,
               size_t n, double error_factor, const TowardsOrigin* towards, float* planes,
               size_t stride) {
  const glm::dvec3 o(origin);
  parallelFor(size_t(0), (n + kCullBlock - 1) / kCullBlock, [&](size_t block) {
    const size_t first = block * kCullBlock;
    float* at = planes + first;
    const int count = int(std::min<size_t>(kCullBlock, n - first));
    if (towards)
      boxesOfBlock<true>(frame, o, triangles + first, count, error_factor, *towards, at,
                         at + stride, at + 2 * stride, at + 3 * stride);
    else
      boxesOfBlock<false>(frame, o, triangles + first, count, error_factor, TowardsOrigin{}, at,
                          at + stride, at + 2 * stride, at + 3 * stride);
  });
}

void boxesOf(const GrCullFrame& frame, const glm::vec3& origin,
             const std::vector<GrTriangle>& triangles, std::vector<CullBox>& boxes,
             double error_factor, const TowardsOrigin* towards) {
  const size_t n = triangles.size();
  std::vector<float> planes(4 * n);
  boxPlanes(frame, origin, triangles.data(), n, error_factor, towards, planes.data(), n);
  boxes.resize(n);
  for (size_t k = 0; k < n; ++k)
    boxes[k] = CullBox{planes[k], planes[n + k], planes[2 * n + k], planes[3 * n + k]};
}

}  // namespace

GrCullFrame cullFrameOf(const PinholeView& view) {
  // The rows of the camera's rotation are its axes in world space; the camera looks down -z.
  const glm::mat4& m = view.world_to_camera;
  const glm::vec3 right = glm::normalize(glm::vec3(m[0][0], m[1][0], m[2][0]));
  const glm::vec3 up = glm::normalize(glm::vec3(m[0][1], m[1][1], m[2][1]));
  const glm::vec3 forward = -glm::normalize(glm::vec3(m[0][2], m[1][2], m[2][2]));
  GrCullFrame frame{};
  frame.fx = forward.x, frame.fy = forward.y, frame.fz = forward.z, frame.enabled = 1.0f;
  frame.rx = right.x, frame.ry = right.y, frame.rz = right.z;
  frame.ux = up.x, frame.uy = up.y, frame.uz = up.z;
  return frame;
}

void cullCoordinates(const GrCullFrame& c, float dx, float dy, float dz, float& a, float& b) {
  const float w = dx * c.fx + dy * c.fy + dz * c.fz;
  a = (dx * c.rx + dy * c.ry + dz * c.rz) / w;
  b = (dx * c.ux + dy * c.uy + dz * c.uz) / w;
}

void computeCullBoxes(const GrCullFrame& frame, const glm::vec3& origin,
                      const std::vector<GrTriangle>& triangles, std::vector<CullBox>& boxes,
                      double error_factor) {
  boxesOf(frame, origin, triangles, boxes, error_factor, nullptr);
}

void computeTowardsOriginBoxes(const GrCullFrame& frame, const glm::vec3& origin,
                               const TowardsOrigin& towards,
                               const std::vector<GrTriangle>& triangles,
                               std::vector<CullBox>& boxes, double error_factor) {
  boxesOf(frame, origin, triangles, boxes, error_factor, &towards);
}

void writeTowardsOriginBoxPlanes(const GrCullFrame& frame, const glm::vec3& origin,
                                 const TowardsOrigin& towards, const GrTriangle* triangles,
                                 size_t count, float* planes, size_t stride) {
  boxPlanes(frame, origin, triangles, count, kCullErrorFactor, &towards, planes, stride);
}

bool CullPlaneCache::update(const GrCullFrame& frame, const glm::vec3& origin,
                            const GrTriangle* triangles, size_t count) {
  const size_t stride = count + kCullPlanePadding;
  if (valid_ && std::memcmp(&frame, &frame_, sizeof frame) == 0 && origin == origin_ &&
      planes_.size() == 4 * stride)
    return false;
  // Sized (and the padding zeroed) once; then every box is written over.
  if (planes_.size() != 4 * stride) {
    reserveFaultedIn(planes_, 4 * stride);  // fresh memory: on every core (prefault.h)
    planes_.assign(4 * stride, 0.0f);
  }
  boxPlanes(frame, origin, triangles, count, kCullErrorFactor, nullptr, planes_.data(), stride);
  frame_ = frame;
  origin_ = origin;
  valid_ = true;
  return true;
}

}  // namespace gridrt
