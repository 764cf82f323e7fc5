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

#include "scene.h"

namespace gridrt {

constexpr int kSurfaceLanes = 16;

// What shading needs from a triangle, made once per scene: its first vertex, its edges
// and their dot products (the barycentrics of a point), the vertex normals (zero when the
// scene has none) and the unit geometric normal.
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

// The surface at one hit: the hit point p = o + t d; the shading normal n (interpolated
// vertex normals when smooth, else the geometric normal) and the geometric normal g, both
// turned to the side the ray came from; backface: the ray hit the side g pointed away
// from. Inline: computeSurfaces runs it in vector lanes.
struct HitSurface {
  float px, py, pz, nx, ny, nz, gx, gy, gz;
  bool backface;
};

inline HitSurface surfaceAt(const ShadingTriangle& tri, bool smooth, float ox, float oy,
                            float oz, float dx, float dy, float dz, float t) {
  HitSurface h;
  h.px = ox + t * dx, h.py = oy + t * dy, h.pz = oz + t * dz;
  float nx = tri.geometric.x, ny = tri.geometric.y, nz = tri.geometric.z;
  if (smooth) {
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
  h.backface = dot3(tri.geometric.x, tri.geometric.y, tri.geometric.z, dx, dy, dz) > 0.0f;
  h.gx = h.backface ? -tri.geometric.x : tri.geometric.x;
  h.gy = h.backface ? -tri.geometric.y : tri.geometric.y;
  h.gz = h.backface ? -tri.geometric.z : tri.geometric.z;
  if (dot3(nx, ny, nz, h.gx, h.gy, h.gz) < 0.0f) nx = -nx, ny = -ny, nz = -nz;
  h.nx = nx, h.ny = ny, h.nz = nz;
  return h;
}

// One per triangle of `scene` (geometric_normals: the renderer's, one per triangle).
std::vector<ShadingTriangle> makeShadingTriangles(const Scene& scene,
                                                  const std::vector<glm::vec3>& geometric_normals);

// 16 hits: the inputs (ray origin and direction, t, triangle) and surfaceAt there.
struct SurfaceLanes {
  alignas(64) float ox[kSurfaceLanes], oy[kSurfaceLanes], oz[kSurfaceLanes];
  alignas(64) float dx[kSurfaceLanes], dy[kSurfaceLanes], dz[kSurfaceLanes];
  alignas(64) float t[kSurfaceLanes];
  alignas(64) int tri[kSurfaceLanes];  // a lane without a hit names any valid triangle
  alignas(64) float px[kSurfaceLanes], py[kSurfaceLanes], pz[kSurfaceLanes];
  alignas(64) float nx[kSurfaceLanes], ny[kSurfaceLanes], nz[kSurfaceLanes];
  alignas(64) float gx[kSurfaceLanes], gy[kSurfaceLanes], gz[kSurfaceLanes];
  alignas(64) int backface[kSurfaceLanes];
};

// Fills the outputs of `s` from its inputs. smooth: interpolate the vertex normals.
void computeSurfaces(const ShadingTriangle* triangles, bool smooth, SurfaceLanes& s);

// One light seen from the 16 hit points: lightIrradiance's direction, distance and
// irradiance, cos_theta = n . to_light, and lit: the light is in front of both normals
// and gives some irradiance (else the hit gets nothing from it and no shadow ray).
struct LightLanes {
  alignas(64) float lx[kSurfaceLanes], ly[kSurfaceLanes], lz[kSurfaceLanes];
  alignas(64) float distance[kSurfaceLanes];
  alignas(64) float ex[kSurfaceLanes], ey[kSurfaceLanes], ez[kSurfaceLanes];
  alignas(64) float cos_theta[kSurfaceLanes];
  alignas(64) int lit[kSurfaceLanes];
};

void computeLightLanes(const Light& light, const SurfaceLanes& s, LightLanes& out);

}  // namespace gridrt
