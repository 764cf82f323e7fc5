// Rays through see-through surfaces: glTF alphaMode MASK (cut-outs) and BLEND (partial
// transmission); docs/gltf.md, "Alpha".
//
// The intersectors find the closest hit of any triangle, as the GridRT reduction decides
// it on the device and the host; the alpha that says whether a hit is a hole lives in the
// textures, which the host holds and reads where it shades. So the host looks at each hit
// on a see-through material and, where it is a hole, traces the ray on from there: the
// same origin and direction with the interval (t of the hole, tmax), which finds the next
// surface along the ray, exactly as the closest hit of the ray past that point. The loop
// ends when every ray has found a surface that is not a hole or left the scene: each
// round's t is larger than the last, and a ray passes each triangle once.
//
// Only rays that hit a see-through material pay: a scene without one skips all of this.
#pragma once
#include <functional>
#include <vector>

#include "gridrt_types.h"
#include "scene.h"
#include "surface_textures.h"

namespace gridrt {

// Traces `rays` to their closest hits (hits resized to rays.size()).
using ClosestTrace = std::function<void(const std::vector<GrRay>&, std::vector<GrHit>&)>;

class SeeThroughHits {
 public:
  // Keeps references to both.
  SeeThroughHits(const Scene& scene, const SurfaceTextures& textures);

  // Whether the scene has a see-through material at all.
  bool active() const { return active_; }

  // How much of the light a hit stops: 1 for an opaque material; for MASK 1 where the
  // alpha reaches alphaCutoff and 0 (a hole) below; for BLEND the alpha, in [0, 1].
  float coverage(const GrRay& ray, const GrHit& hit) const;

  // Closest hits: every hit on a hole (coverage 0) replaced by the closest surface past it
  // that is not a hole, or a miss. Returns the rays traced again.
  size_t passHoles(const std::vector<GrRay>& rays, std::vector<GrHit>& hits,
                   const ClosestTrace& trace);

  // Shadow rays: from any hits (HitMode::AnyHit; prim < 0: none), the share of the light
  // that reaches each ray's end: 1 without a hit, 0 when a surface of coverage 1 blocks
  // it, else the product of (1 - coverage) over the surfaces along the ray. Returns the
  // rays traced again.
  size_t transmittance(const std::vector<GrRay>& rays, const std::vector<GrHit>& any_hits,
                       const ClosestTrace& trace, std::vector<float>& light_share);

 private:
  const Scene& scene_;
  const SurfaceTextures& textures_;
  bool active_ = false;
  // Scratch of the rounds, kept from call to call.
  std::vector<size_t> pending_;
  std::vector<char> hole_;  // per pending ray: its hit is a hole
  std::vector<GrRay> onward_rays_;
  std::vector<GrHit> onward_hits_;
};

}  // namespace gridrt
