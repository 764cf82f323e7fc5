// The surfaces at 16 hits at a time, in lanes (structure of arrays): hit point, shading
// normal and geometric normal, and per light the direction, distance, irradiance and
// whether it lights the hit. The shading loop used to compute these one hit at a time;
// here each lane does the same operations in the same order (GLM's: a dot product is
// (x + y) + z, a length the square root of that), so every value is bit for bit what the
// one-hit code gave, while the compiler runs the lanes in vector registers.
#pragma once
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

// One per triangle of `scene` (geometric_normals: the renderer's, one per triangle).
std::vector<ShadingTriangle> makeShadingTriangles(const Scene& scene,
                                                  const std::vector<glm::vec3>& geometric_normals);

// 16 hits: the inputs (ray origin and direction, t, triangle) and the surface there.
struct SurfaceLanes {
  alignas(64) float ox[kSurfaceLanes], oy[kSurfaceLanes], oz[kSurfaceLanes];
  alignas(64) float dx[kSurfaceLanes], dy[kSurfaceLanes], dz[kSurfaceLanes];
  alignas(64) float t[kSurfaceLanes];
  alignas(64) int tri[kSurfaceLanes];  // a lane without a hit names any valid triangle
  // Outputs: the hit point p = o + t d; the shading normal n (interpolated vertex normals,
  // the geometric normal without them) and the geometric normal g, both turned to the
  // side the ray came from; backface: the ray hit the side g pointed away from.
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
