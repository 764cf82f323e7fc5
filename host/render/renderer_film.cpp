// What a wave leaves in the film: each depth's radiance and its unoccluded shadow rays'
// light added in a depth-by-depth renderer's order, coverage for alpha, the primary AOVs.
#include "parallel_loops.h"
#include "renderer.h"

namespace gridrt {

namespace {

// Calls add(i) for every i in [0, n) in parallel slices, where pixel_of(i) is the pixel entry i
// adds to and each pixel's entries are consecutive (so in every generation: a pixel's
// samples are consecutive in the primary order, and spawned rays and shadow rays follow
// the order of the rays that spawned them). The slices' ranges end between pixels: no
// two slices share a pixel, and each pixel's sum keeps the serial order.
template <typename PixelOf, typename Add>
void addInPixelRuns(size_t n, const PixelOf& pixel_of, const Add& add) {
  parallelSlices(parallelSliceCount(), [&](size_t me, size_t slices) {
    auto boundary = [&](size_t k) {
      size_t i = n * k / slices;
      while (i > 0 && i < n && pixel_of(i) == pixel_of(i - 1)) ++i;
      return i;
    };
    const size_t hi = boundary(me + 1);
    for (size_t i = boundary(me); i < hi; ++i) add(i);
  });
}

}  // namespace

void Renderer::addPassRadiance(int depths, PrimaryPaths primary) {
  for (int depth = 0; depth < depths; ++depth) {
    const Generation& g = generations_[depth];
    const std::vector<glm::vec3>& local = g.radiance;
    if (depth > 0) {
      const std::vector<PathRay>& ps = g.paths;
      addInPixelRuns(
          ps.size(), [&](size_t i) { return ps[i].pixel; },
          [&](size_t i) { radiance_.add(ps[i].pixel, local[i]); });
    } else if (!g.radiance_in_pixels) {
      // Primary rays: each pixel's samples are consecutive, pixels distinct.
      parallelFor(0LL, (long long)((local.size() / primary.spp)), [&](long long k) {
        for (int s = 0; s < primary.spp; ++s)
          radiance_.add(window_pixels_[k], local[size_t(k) * primary.spp + s]);
      });
    }
    const ShadowRay* shadows = shadows_.data() + g.first_shadow;
    const GrHit* hits = shadow_hits_.data() + g.first_shadow;
    addInPixelRuns(
        g.shadow_count, [&](size_t k) { return shadows[k].pixel; },
        [&](size_t k) {
          if (hits[k].prim < 0) radiance_.add(shadows[k].pixel, shadows[k].radiance);
        });
  }
}

void Renderer::countCoverage(const std::vector<GrHit>& hits, int spp) {
  parallelFor(0LL, (long long)(window_pixels_.size()), [&](long long k) {
    uint32_t hit = 0;
    for (int s = 0; s < spp; ++s) hit += hits[size_t(k) * spp + s].prim >= 0;
    coverage_.add(size_t(window_pixels_[k]), hit, uint32_t(spp));
  });
}

void Renderer::fillPrimaryAovs(PrimaryAovs& a, const std::vector<GrRay>& rays,
                               const std::vector<GrHit>& hits, const RayDiagnostics& diagnostics,
                               int spp) {
  const bool diag = settings_.want_diagnostics;
  const ShadingTriangle* smooth_triangles =
      shading_triangles_.empty() ? nullptr : shading_triangles_.data();
  parallelFor(0LL, (long long)(window_pixels_.size()), [&](long long k) {
    size_t p = size_t(window_pixels_[k]), r = size_t(k) * spp;  // sample 0 of the pixel
    const GrHit& hit = hits[r];
    if (hit.prim >= 0) {
      a.depth[p] = hit.t;
      a.primid[p] = hit.prim;
      for (int c = 0; c < 3; ++c) a.normal[3 * p + c] = geometric_normals_[hit.prim][c];
      const PrimarySurface surface = primarySurface(hit, rays[r], smooth_triangles);
      for (int c = 0; c < 3; ++c) {
        a.shading_normal[3 * p + c] = surface.normal[c];
        a.albedo[3 * p + c] = surface.base_color[c];
      }
    }
    if (diag) {
      a.tests[p] = float(diagnostics.tests[r]);
      a.pe[p] = diagnostics.winning_pe[r];
      a.list_length[p] = float(diagnostics.list_length[r]);
    }
  });
}

}  // namespace gridrt
