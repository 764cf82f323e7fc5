// The surfaces at 16 hits at a time, in lanes (structure of arrays): hit point, shading
// normal and geometric normal, and per light the direction, distance, irradiance and
// whether it lights the hit. The shading loop used to compute these one hit at a time;
// here each lane does the same operations in the same order (GLM's: a dot product is
// (x + y) + z, a length the square root of that), so every value is bit for bit what the
// one-hit code gave, while the compiler runs the lanes in vector registers.
#pragma once
#include <cmath>
#include <glm/glm.hpp>
#include <vector>

#include "gridrt_types.h"
#include "scene.h"

namespace gridrt {

// Hits shaded at a time: a width of the host's vector registers, independent of the
// kernels' packets (GR_PACKET_LANES): the hits come in shading order, not by packet.
constexpr int kSurfaceLanes = 16;

// What interpolating a triangle's vertex normals needs, made once per scene: its first
// vertex, its edges and their dot products (the barycentrics of a point), the vertex
// normals, and the unit geometric normal (read from here too: one place per hit).
struct ShadingTriangle {
  glm::vec3 v0, e1, e2;
  float d11, d12, d22, det;  // e1.e1, e1.e2, e2.e2, d11 d22 - d12^2
  glm::vec3 n0, n1, n2;
  glm::vec3 geometric;
};

// GLM's dot product of two vec3s, (x + y) + z.
inline float dot3(float ax, float ay, float az, float bx, float by, float bz) {
  return ax * bx + ay * by + az * bz;
}

// The surface at one hit: the hit point p = o + t d; the shading normal n (kSmooth: the
// interpolated vertex normals of *smooth; else the geometric normal) and the geometric
// normal g (unit, the triangle's), both turned to the side the ray came from; backface:
// the ray hit the side g pointed away from. Inline: computeSurfaces runs it in vector
// lanes.
struct HitSurface {
  float px, py, pz, nx, ny, nz, gx, gy, gz;
  bool backface;
};

template <bool kSmooth>
inline HitSurface surfaceAt(const ShadingTriangle* smooth, glm::vec3 geometric, float ox, float oy,
                            float oz, float dx, float dy, float dz, float t) {
  HitSurface h;
  h.px = ox + t * dx, h.py = oy + t * dy, h.pz = oz + t * dz;
  const float gx = geometric.x, gy = geometric.y, gz = geometric.z;
  float nx = gx, ny = gy, nz = gz;
  if constexpr (kSmooth) {
    const ShadingTriangle& tri = *smooth;
    // Barycentrics of p in the file's vertex order (the kernels' u, v refer to the
    // canonical order of prepareTriangles); a degenerate triangle weighs all three alike.
    const float wx = h.px - tri.v0.x, wy = h.py - tri.v0.y, wz = h.pz - tri.v0.z;
    const float w1 = dot3(wx, wy, wz, tri.e1.x, tri.e1.y, tri.e1.z);
    const float w2 = dot3(wx, wy, wz, tri.e2.x, tri.e2.y, tri.e2.z);
    const bool solid = tri.det > 0.0f;
    const float b1 = solid ? (tri.d22 * w1 - tri.d12 * w2) / tri.det : 1.0f / 3.0f;
    const float b2 = solid ? (tri.d11 * w2 - tri.d12 * w1) / tri.det : 1.0f / 3.0f;
    const float b0 = solid ? 1.0f - b1 - b2 : 1.0f / 3.0f;
    const float sx = b0 * tri.n0.x + b1 * tri.n1.x + b2 * tri.n2.x;
    const float sy = b0 * tri.n0.y + b1 * tri.n1.y + b2 * tri.n2.y;
    const float sz = b0 * tri.n0.z + b1 * tri.n1.z + b2 * tri.n2.z;
    const float len = std::sqrt(dot3(sx, sy, sz, sx, sy, sz));
    if (len > 0.0f) nx = sx / len, ny = sy / len, nz = sz / len;
  }
  h.backface = dot3(gx, gy, gz, dx, dy, dz) > 0.0f;
  h.gx = h.backface ? -gx : gx;
  h.gy = h.backface ? -gy : gy;
  h.gz = h.backface ? -gz : gz;
  if (dot3(nx, ny, nz, h.gx, h.gy, h.gz) < 0.0f) nx = -nx, ny = -ny, nz = -nz;
  h.nx = nx, h.ny = ny, h.nz = nz;
  return h;
}

// One per triangle of `scene` (geometric_normals: one per triangle); none when it has no
// vertex normals (then a hit needs only its geometric normal).
std::vector<ShadingTriangle> makeShadingTriangles(const Scene& scene,
                                                  const std::vector<glm::vec3>& geometric_normals);

// 16 hits: the inputs (ray origin and direction, t, triangle) and surfaceAt there.
struct SurfaceLanes {
  alignas(64) float ox[kSurfaceLanes], oy[kSurfaceLanes], oz[kSurfaceLanes];
  alignas(64) float dx[kSurfaceLanes], dy[kSurfaceLanes], dz[kSurfaceLanes];
  alignas(64) float t[kSurfaceLanes];
  alignas(64) int tri[kSurfaceLanes];  // lanes past a block's hits copy lane 0
  alignas(64) float px[kSurfaceLanes], py[kSurfaceLanes], pz[kSurfaceLanes];
  alignas(64) float nx[kSurfaceLanes], ny[kSurfaceLanes], nz[kSurfaceLanes];
  alignas(64) float gx[kSurfaceLanes], gy[kSurfaceLanes], gz[kSurfaceLanes];
  alignas(64) int backface[kSurfaceLanes];

  // Lane k's inputs: `ray` and its hit.
  void setHit(int k, const GrRay& ray, const GrHit& hit) {
    ox[k] = ray.ox, oy[k] = ray.oy, oz[k] = ray.oz;
    dx[k] = ray.dx, dy[k] = ray.dy, dz[k] = ray.dz;
    t[k] = hit.t;
    tri[k] = hit.prim;
  }
  // A block of `count` hits (at least one): the inputs of the lanes past it, copies of lane 0.
  void padFrom(int count) {
    for (int k = count; k < kSurfaceLanes; ++k) {
      ox[k] = ox[0], oy[k] = oy[0], oz[k] = oz[0];
      dx[k] = dx[0], dy[k] = dy[0], dz[k] = dz[0];
      t[k] = t[0], tri[k] = tri[0];
    }
  }
};

// Fills the outputs of `s` from its inputs: surfaceAt in every lane (triangles: the
// scene's shading triangles, null without vertex normals; geometric: its unit normals).
void computeSurfaces(const ShadingTriangle* triangles, const glm::vec3* geometric, SurfaceLanes& s);

// surfaceAt for one hit of triangle `tri` (triangles and geometric as for computeSurfaces).
inline HitSurface surfaceOfHit(const ShadingTriangle* triangles, const glm::vec3* geometric,
                               int tri, float ox, float oy, float oz, float dx, float dy, float dz,
                               float t) {
  return triangles ? surfaceAt<true>(&triangles[tri], geometric[tri], ox, oy, oz, dx, dy, dz, t)
                   : surfaceAt<false>(nullptr, geometric[tri], ox, oy, oz, dx, dy, dz, t);
}

// One light seen from the 16 hit points: lightIrradiance's direction, distance and
// irradiance, cos_theta = n . to_light, and lit: the light is in front of both normals
// and gives some irradiance (else the hit gets nothing from it and no shadow ray).
struct LightLanes {
  alignas(64) float lx[kSurfaceLanes], ly[kSurfaceLanes], lz[kSurfaceLanes];
  alignas(64) float distance[kSurfaceLanes];
  alignas(64) float ex[kSurfaceLanes], ey[kSurfaceLanes], ez[kSurfaceLanes];
  alignas(64) float cos_theta[kSurfaceLanes];
  alignas(64) int lit[kSurfaceLanes];
  // Phong only: the highlight's cosine and power (phong_highlights.h).
  alignas(64) float rv[kSurfaceLanes], highlight[kSurfaceLanes];
};

void computeLightLanes(const Light& light, const SurfaceLanes& s, LightLanes& out);

}  // namespace gridrt
