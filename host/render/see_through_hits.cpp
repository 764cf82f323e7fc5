#include "see_through_hits.h"

#include <algorithm>

#include "parallel_loops.h"

namespace gridrt {

SeeThroughHits::SeeThroughHits(const Scene& scene, const SurfaceTextures& textures)
    : scene_(scene), textures_(textures) {
  for (const Material& m : scene.materials) active_ = active_ || m.seeThrough();
}

float SeeThroughHits::coverage(const GrRay& ray, const GrHit& hit) const {
  const Material& m = scene_.materials[size_t(scene_.material_of[size_t(hit.prim)])];
  if (!m.seeThrough()) return 1.0f;
  // The hit point as the shading computes it (surfaceAt, hit_surfaces.h).
  const glm::vec3 p(ray.ox + hit.t * ray.dx, ray.oy + hit.t * ray.dy, ray.oz + hit.t * ray.dz);
  const float alpha = textures_.alphaAt(hit.prim, p);
  if (m.alpha_mode == AlphaMode::Mask) return alpha >= m.alpha_cutoff ? 1.0f : 0.0f;
  // A share of the light even where a file's factor lies outside [0, 1].
  return std::clamp(alpha, 0.0f, 1.0f);
}

size_t SeeThroughHits::passHoles(const std::vector<GrRay>& rays, std::vector<GrHit>& hits,
                                 const ClosestTrace& trace) {
  if (!active_) return 0;
  size_t traced = 0;
  pending_.clear();
  for (size_t i = 0; i < rays.size(); ++i) pending_.push_back(i);
  while (!pending_.empty()) {
    // The rays whose hit is a hole go on from it.
    hole_.resize(pending_.size());
    parallelFor(0LL, (long long)(pending_.size()), [&](long long k) {
      const GrHit& hit = hits[pending_[k]];
      hole_[k] = hit.prim >= 0 && coverage(rays[pending_[k]], hit) == 0.0f;
    });
    size_t kept = 0;
    onward_rays_.clear();
    for (size_t k = 0; k < pending_.size(); ++k) {
      if (!hole_[k]) continue;
      GrRay onward = rays[pending_[k]];
      onward.tmin = hits[pending_[k]].t;
      onward_rays_.push_back(onward);
      pending_[kept++] = pending_[k];
    }
    pending_.resize(kept);
    if (pending_.empty()) break;
    trace(onward_rays_, onward_hits_);
    traced += onward_rays_.size();
    for (size_t k = 0; k < pending_.size(); ++k) {
      GrHit& hit = hits[pending_[k]];
      const GrHit& next = onward_hits_[k];
      // The next surface lies beyond the hole; an intersector that gave back the hole
      // itself (t not beyond it) would loop forever: that ray ends as a miss instead.
      hit = next.prim >= 0 && next.t > hit.t ? next : GrHit{0.0f, -1, 0.0f, 0.0f};
    }
  }
  return traced;
}

size_t SeeThroughHits::transmittance(const std::vector<GrRay>& rays,
                                     const std::vector<GrHit>& any_hits, const ClosestTrace& trace,
                                     std::vector<float>& light_share) {
  light_share.assign(rays.size(), 1.0f);
  // Any hit on a surface of coverage 1 blocks the light; a ray whose any hit is see-through
  // may still be blocked nearer, so it is traced again from its start, surface by surface.
  pending_.clear();
  for (size_t i = 0; i < rays.size(); ++i) {
    if (any_hits[i].prim < 0) continue;
    if (coverage(rays[i], any_hits[i]) >= 1.0f)
      light_share[i] = 0.0f;
    else
      pending_.push_back(i);
  }
  size_t traced = 0;
  std::vector<float> tmin;
  for (size_t i : pending_) tmin.push_back(rays[i].tmin);
  while (!pending_.empty()) {
    onward_rays_.clear();
    for (size_t k = 0; k < pending_.size(); ++k) {
      GrRay onward = rays[pending_[k]];
      onward.tmin = tmin[k];
      onward_rays_.push_back(onward);
    }
    trace(onward_rays_, onward_hits_);
    traced += onward_rays_.size();
    size_t kept = 0;
    for (size_t k = 0; k < pending_.size(); ++k) {
      const size_t i = pending_[k];
      const GrHit& hit = onward_hits_[k];
      if (hit.prim < 0) continue;  // the rest of the way is clear
      if (!(hit.t > tmin[k])) {    // not beyond the last surface: end as blocked
        light_share[i] = 0.0f;
        continue;
      }
      light_share[i] *= 1.0f - coverage(onward_rays_[k], hit);
      if (light_share[i] <= 0.0f) continue;
      pending_[kept] = i;
      tmin[kept++] = hit.t;
    }
    pending_.resize(kept);
    tmin.resize(kept);
  }
  return traced;
}

}  // namespace gridrt
