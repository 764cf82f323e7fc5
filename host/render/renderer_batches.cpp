// The batches: a generation's rays handed to the intersector in batches that fit the
// device, camera rays through the camera's own path, shadow rays light by light.
#include <algorithm>

#include "camera_rays.h"
#include "parallel_loops.h"
#include "prefault.h"
#include "renderer.h"
#include "stopwatch.h"

namespace gridrt {

namespace {

// Diagnostics of one batch appended after those of the batches before it.
void appendDiagnostics(RayDiagnostics& all, const RayDiagnostics& batch) {
  auto append = [](std::vector<int>& to, const std::vector<int>& from) {
    to.insert(to.end(), from.begin(), from.end());
  };
  append(all.tests, batch.tests);
  append(all.winning_pe, batch.winning_pe);
  append(all.list_length, batch.list_length);
}

}  // namespace

void Renderer::traceInBatches(const std::vector<GrRay>& rays, std::vector<GrHit>& hits,
                              RayDiagnostics* diagnostics, double& ms, const BatchTrace& trace) {
  Stopwatch clock;
  if (rays.size() <= kMaxBatchRays) {
    trace(rays, hits, diagnostics);
  } else {
    resizeFaultedIn(hits, rays.size());
    RayDiagnostics part;
    if (diagnostics) *diagnostics = RayDiagnostics{};
    for (size_t first = 0; first < rays.size(); first += kMaxBatchRays) {
      size_t count = std::min(kMaxBatchRays, rays.size() - first);
      batch_rays_.assign(rays.begin() + first, rays.begin() + first + count);
      trace(batch_rays_, batch_hits_, diagnostics ? &part : nullptr);
      std::copy(batch_hits_.begin(), batch_hits_.end(), hits.begin() + first);
      if (diagnostics) appendDiagnostics(*diagnostics, part);
    }
  }
  ms += clock.ms();
}

void Renderer::traceBatched(const std::vector<GrRay>& rays, HitMode mode, std::vector<GrHit>& hits,
                            RayDiagnostics* diagnostics, double& ms) {
  traceInBatches(rays, hits, diagnostics, ms,
                 [&](const std::vector<GrRay>& batch, std::vector<GrHit>& out, RayDiagnostics* d) {
                   intersector_.intersect(batch, mode, out, d);
                 });
}

void Renderer::splitShadowsByLight() {
  const size_t lights = lights_.size(), n = shadows_.size();
  const int slices = parallelSliceCount();
  slice_light_counts_.resize(slices);
  parallelSlices(slices, [&](int me, int count) {
    std::vector<size_t>& counts = slice_light_counts_[me];
    counts.assign(lights, 0);
    const auto [first, last] = sliceRange(n, me, count);
    for (size_t k = first; k < last; ++k) ++counts[size_t(shadows_[k].light)];
  });
  // Each slice's first position in each light's rays: the earlier slices' counts before it.
  light_rays_.resize(lights);
  light_ray_index_.resize(lights);
  for (size_t l = 0; l < lights; ++l) {
    size_t offset = 0;
    for (std::vector<size_t>& counts : slice_light_counts_) {
      const size_t c = counts[l];
      counts[l] = offset;
      offset += c;
    }
    resizeFaultedIn(light_rays_[l], offset);
    resizeFaultedIn(light_ray_index_[l], offset);
  }
  parallelSlices(slices, [&](int me, int count) {
    std::vector<size_t>& next = slice_light_counts_[me];
    const auto [first, last] = sliceRange(n, me, count);
    for (size_t k = first; k < last; ++k) {
      const size_t l = size_t(shadows_[k].light), at = next[l]++;
      light_rays_[l][at] = shadow_rays_[k];
      light_ray_index_[l][at] = k;
    }
  });
}

void Renderer::traceShadows(double& ms, uint64_t& see_through_rays) {
  resizeFaultedIn(shadow_hits_, shadow_rays_.size());
  // With one light its rays are all the shadow rays.
  const bool all = lights_.size() == 1;
  if (!all) splitShadowsByLight();
  for (size_t l = 0; l < lights_.size(); ++l) {
    const Light& light = lights_[l];
    const std::vector<GrRay>& rays = all ? shadow_rays_ : light_rays_[l];
    std::vector<GrHit>& hits = all ? shadow_hits_ : light_hits_;
    if (rays.empty()) continue;
    if (light.type == LightType::Directional) {
      traceBatched(rays, HitMode::AnyHit, hits, nullptr, ms);
    } else {  // every ray ends at the light: the intersector may bundle them
      traceInBatches(
          rays, hits, nullptr, ms,
          [&](const std::vector<GrRay>& batch, std::vector<GrHit>& out, RayDiagnostics*) {
            intersector_.intersectTowardsPoint(light.position, batch, HitMode::AnyHit, out);
          });
    }
    if (!all) {
      const std::vector<size_t>& index = light_ray_index_[l];
      parallelFor(size_t(0), index.size(), [&](size_t i) { shadow_hits_[index[i]] = hits[i]; });
    }
  }
  if (!see_through_.active()) return;
  // Past MASK holes and through BLEND surfaces: the light that gets through reaches the
  // pixel (as if unoccluded), scaled by its share.
  see_through_rays += see_through_.transmittance(
      shadow_rays_, shadow_hits_,
      [&](const std::vector<GrRay>& rays, std::vector<GrHit>& hits) {
        traceBatched(rays, HitMode::Closest, hits, nullptr, ms);
      },
      shadow_light_share_);
  parallelFor(size_t(0), shadow_rays_.size(), [&](size_t k) {
    if (shadow_light_share_[k] > 0.0f && shadow_hits_[k].prim >= 0) {
      shadow_hits_[k].prim = -1;
      shadows_[k].radiance *= shadow_light_share_[k];
    }
  });
}

void Renderer::tracePrimary(const PixelWindow& window, std::vector<GrHit>& hits,
                            RayDiagnostics* diagnostics, double& ms) {
  Stopwatch clock;
  const CameraRayGenerator camera_rays(camera_, settings_.width, settings_.height);
  PinholeView view = PinholeView::of(camera_, settings_.width, settings_.height, window);
  intersector_.generateAndIntersectPrimary(view, camera_rays, primary_rays_, hits, diagnostics);
  ms += clock.ms();
}

}  // namespace gridrt
