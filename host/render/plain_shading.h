// The Whitted loop's work for hits on plain surfaces, 16 hits at a time. A plain surface
// (Phong shading; a material without textures or vertex colours, blending or an absorbing
// volume) gives a hit its own light (emissive and ambient), a shadow ray per lit light,
// and where it mirrors or transmits, a reflection and a refraction ray. Every value is
// computed in lanes with the operations of the one-hit loop (Renderer::shadeWhitted) in
// its order, so both give the same bits; a lane whose material is not plain, or whose
// point, origin or normal is not finite, is left to the one-hit loop.
#pragma once
#include <glm/glm.hpp>
#include <vector>

#include "hit_surfaces.h"
#include "whitted_shading.h"

namespace gridrt {

// What a hit on one material needs of it on the plain path.
struct PlainMaterial {
  int plain = 0;  // 1: hits on it take the plain path
  glm::vec3 diffuse{0.0f}, specular{0.0f}, emissive{0.0f};
  int spawning = 0;  // 1: its hits spawn rays (it mirrors or transmits)
  // SurfaceTerms::mirror and ::transmission, the base colour and index of refraction.
  glm::vec3 mirror{0.0f}, base_color{0.0f};
  float transmission = 0.0f, ior = 1.5f;
};

// A block's plain-path values: weight and material are the inputs (every lane set; lanes
// past the block's hits copy lane 0), the rest the outputs.
struct PlainLanes {
  alignas(64) float wr[kSurfaceLanes], wg[kSurfaceLanes], wb[kSurfaceLanes];  // path weight
  alignas(64) int material[kSurfaceLanes];
  alignas(64) int plain[kSurfaceLanes];  // the lane takes the plain path
  // The hit's own light, weight * (emissive + ambient * diffuse).
  alignas(64) float lr[kSurfaceLanes], lg[kSurfaceLanes], lb[kSurfaceLanes];
  alignas(64) float offset[kSurfaceLanes];  // rayOffsetDistance: the shadow rays' tmin
  // offsetRayOrigin: where the shadow rays start.
  alignas(64) float ax[kSurfaceLanes], ay[kSurfaceLanes], az[kSurfaceLanes];
};

// The rays a block's plain lanes spawn (computeSpawnLanes), as the one-hit loop makes them:
// first the refraction ray, then the reflection ray.
struct SpawnLanes {
  alignas(64) int refract[kSurfaceLanes];  // a refraction ray worth tracing
  // offsetRayOrigin below the surface, refractDirection, the path weight.
  alignas(64) float rox[kSurfaceLanes], roy[kSurfaceLanes], roz[kSurfaceLanes];
  alignas(64) float rdx[kSurfaceLanes], rdy[kSurfaceLanes], rdz[kSurfaceLanes];
  alignas(64) float rwr[kSurfaceLanes], rwg[kSurfaceLanes], rwb[kSurfaceLanes];
  alignas(64) int reflect[kSurfaceLanes];  // a reflection ray worth tracing (from ax, ay, az)
  alignas(64) float fdx[kSurfaceLanes], fdy[kSurfaceLanes], fdz[kSurfaceLanes];
  alignas(64) float fwr[kSurfaceLanes], fwg[kSurfaceLanes], fwb[kSurfaceLanes];
};

// One light's share of a block's plain lanes.
struct PlainLightLanes {
  // weight * (diffuse / pi * e * cos_theta + specular * e * highlight)
  alignas(64) float cr[kSurfaceLanes], cg[kSurfaceLanes], cb[kSurfaceLanes];
  alignas(64) int emit[kSurfaceLanes];  // lit and the contribution not zero: a shadow ray
};

// The surfaces `s` of a block (hit points, geometric normals, ray origins) on the plain path.
void computePlainLanes(const SurfaceLanes& s, const PlainMaterial* materials, float ambient,
                       const RayOffset& offset, PlainLanes& p);

// The reflection and refraction rays of the plain lanes of `p` (after computePlainLanes):
// worth tracing where the largest component of their weight reaches min_path_weight. A
// lane whose origin below the surface is not finite leaves the plain path (p.plain).
void computeSpawnLanes(const SurfaceLanes& s, const PlainMaterial* materials,
                       const RayOffset& offset, float min_path_weight, PlainLanes& p,
                       SpawnLanes& out);

// Light `light`'s contributions to the plain lanes of `p` (Phong: `light` has highlights).
void computePlainLight(const PlainLanes& p, const PlainMaterial* materials, const LightLanes& light,
                       PlainLightLanes& out);

}  // namespace gridrt
