#include "renderer.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "bounds.h"
#include "camera_rays.h"
#include "default_lighting.h"
#include "parallel_loops.h"
#include "phong_highlights.h"
#include "pixel_blocks.h"
#include "prefault.h"
#include "prepared_triangles.h"
#include "stopwatch.h"

namespace gridrt {

namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();

GrRay makeRay(const glm::vec3& o, const glm::vec3& d, float tmax, float tmin = 0.0f) {
  return GrRay{o.x, o.y, o.z, tmin, d.x, d.y, d.z, tmax};
}

// Diagnostics of one batch appended after those of the batches before it.
void appendDiagnostics(RayDiagnostics& all, const RayDiagnostics& batch) {
  auto append = [](std::vector<int>& to, const std::vector<int>& from) {
    to.insert(to.end(), from.begin(), from.end());
  };
  append(all.tests, batch.tests);
  append(all.winning_pe, batch.winning_pe);
  append(all.list_length, batch.list_length);
}

glm::vec3 reflectDirection(const glm::vec3& d, const glm::vec3& n) {
  return d - 2.0f * glm::dot(d, n) * n;
}

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

// The next free index of two parallel vectors whose first `count` elements are in use
// (both grown when full): the shading loop writes its outputs in place, and its buffers
// keep their sizes between frames.
template <typename A, typename B>
size_t nextSlot(std::vector<A>& a, std::vector<B>& b, size_t& count) {
  if (count == a.size()) {
    a.resize(std::max<size_t>(256, 2 * count));
    b.resize(a.size());
  }
  return count++;
}

// `w` with one more pixel on each side, inside the width x height image.
PixelWindow grownInside(const PixelWindow& w, int width, int height) {
  return PixelWindow{std::max(0, w.x0 - 1), std::max(0, w.y0 - 1), std::min(width, w.x1 + 1),
                     std::min(height, w.y1 + 1)};
}

// Keeps the pixels of `inner` (inside `outer`) of an image of `outer`'s pixels with
// `channels` floats each, in place, row by row.
template <typename T>
void keepWindow(std::vector<T>& image, const PixelWindow& outer, const PixelWindow& inner,
                int channels) {
  if (image.empty()) return;
  const size_t row = size_t(inner.width()) * channels;
  for (int y = inner.y0; y < inner.y1; ++y) {
    const size_t from = (size_t(y - outer.y0) * outer.width() + (inner.x0 - outer.x0)) * channels;
    std::copy_n(image.begin() + from, row, image.begin() + size_t(y - inner.y0) * row);
  }
  image.resize(row * inner.height());
}

}  // namespace

Renderer::Renderer(const Scene& scene, const Camera& camera, Intersector& intersector,
                   RenderSettings settings)
    : scene_(scene),
      camera_(camera),
      intersector_(intersector),
      settings_(settings),
      surface_textures_(scene),
      see_through_(scene, surface_textures_),
      output_window_(settings.crop.orWholeImage(settings.width, settings.height)),
      film_window_(settings.adaptive_aa
                       ? grownInside(output_window_, settings.width, settings.height)
                       : output_window_) {
  geometric_normals_.resize(scene.triangleCount());
  for (size_t t = 0; t < scene.triangleCount(); ++t) {
    glm::vec3 n = glm::cross(scene.positions[3 * t + 1] - scene.positions[3 * t],
                             scene.positions[3 * t + 2] - scene.positions[3 * t]);
    float len = glm::length(n);
    geometric_normals_[t] = len > 0.0f ? n / len : glm::vec3(0.0f, 0.0f, 1.0f);
  }
  shading_triangles_ = makeShadingTriangles(scene, geometric_normals_);
  lights_ = scene.has_lights ? scene.lights : defaultLights(camera);
  for (const Material& m : scene.materials) material_terms_.push_back(surfaceTerms(m));
  // Plain: nothing of the material varies over a surface, nor is light absorbed inside it
  // (a hit's weight is its path's).
  for (size_t i = 0; i < scene.materials.size(); ++i) {
    const Material& m = scene.materials[i];
    const SurfaceTerms& t = material_terms_[i];
    PlainMaterial& p = plain_materials_.emplace_back();
    p.plain = !surface_textures_.varies(int(i)) && m.alpha_mode != AlphaMode::Blend &&
              !(m.transmission > 0.0f && m.attenuation_distance > 0.0f);
    p.spawning = t.transmission > 0.0f || t.mirror != glm::vec3(0.0f);
    p.diffuse = t.diffuse;
    p.specular = t.specular;
    p.emissive = m.emissive;
    p.mirror = t.mirror;
    p.base_color = m.base_color;
    p.transmission = t.transmission;
    p.ior = m.ior;
  }
  // One pixel's width: at the camera for an orthographic camera, per unit distance else.
  const float rows = float(std::max(1, settings.height));
  if (camera.orthographic)
    cone_origin_ = 2.0f * camera.ymag / rows;
  else
    cone_spread_ = 2.0f * std::tan(0.5f * camera.yfov) / rows;
}

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

void Renderer::traceShadows(double& ms, uint64_t& see_through_rays) {
  resizeFaultedIn(shadow_hits_, shadow_rays_.size());
  for (size_t l = 0; l < lights_.size(); ++l) {
    const Light& light = lights_[l];
    // This light's rays (all of them when it is the only light).
    const bool all = lights_.size() == 1;
    light_ray_index_.clear();
    light_rays_.clear();
    if (!all)
      for (size_t k = 0; k < shadows_.size(); ++k)
        if (shadows_[k].light == int(l)) {
          light_ray_index_.push_back(k);
          light_rays_.push_back(shadow_rays_[k]);
        }
    const std::vector<GrRay>& rays = all ? shadow_rays_ : light_rays_;
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
    if (!all)
      for (size_t i = 0; i < light_ray_index_.size(); ++i)
        shadow_hits_[light_ray_index_[i]] = hits[i];
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
  for (size_t k = 0; k < shadow_rays_.size(); ++k)
    if (shadow_light_share_[k] > 0.0f && shadow_hits_[k].prim >= 0) {
      shadow_hits_[k].prim = -1;
      shadows_[k].radiance *= shadow_light_share_[k];
    }
}

void Renderer::tracePrimary(const PixelWindow& window, std::vector<GrHit>& hits,
                            RayDiagnostics* diagnostics, double& ms) {
  Stopwatch clock;
  const CameraRayGenerator camera_rays(camera_, settings_.width, settings_.height);
  PinholeView view = PinholeView::of(camera_, settings_.width, settings_.height, window);
  intersector_.generateAndIntersectPrimary(view, camera_rays, primary_rays_, hits, diagnostics);
  ms += clock.ms();
}

void Renderer::render(Frame& frame, const std::function<void(int, int)>& progress) {
  Stopwatch frame_clock;
  // The film holds the window's pixels alone (the whole image without a crop), so a tile
  // of a large image needs the memory of the tile: pixel (x, y) is film pixel
  // (y - win.y0) * fw + (x - win.x0).
  const PixelWindow& win = film_window_;
  const int fw = win.width(), fh = win.height();
  const size_t pixels = size_t(fw) * fh;
  frame.rays = RayCounts{};
  frame.times = FrameTimes{};
  frame.refined_pixels = 0;
  frame.passes = 0;
  resizeFaultedIn(radiance_, pixels);
  parallelFor(int(0), int(fh), [&](int y) {
    std::fill(radiance_.begin() + size_t(y) * fw, radiance_.begin() + size_t(y + 1) * fw,
              glm::vec3(0.0f));
  });
  if (settings_.want_alpha) coverage_.reset(pixels);
  if (settings_.want_aovs || settings_.want_diagnostics) {
    const bool diag = settings_.want_diagnostics;
    PrimaryAovs& a = frame.aovs;
    a.depth.assign(pixels, -1.0f);
    a.primid.assign(pixels, -1);
    a.normal.assign(pixels * 3, 0.0f);
    a.shading_normal.assign(pixels * 3, 0.0f);
    a.albedo.assign(pixels * 3, 0.0f);
    a.tests.assign(diag ? pixels : 0, 0.0f);
    a.pe.assign(diag ? pixels : 0, -1);
    a.list_length.assign(diag ? pixels : 0, 0.0f);
  }

  if (!settings_.adaptive_aa) {
    const int spp = std::max(1, settings_.spp);
    renderInBands(frame, win, spp, 1.0f / float(spp), progress);
  } else {
    // Adaptive supersampling: the pixel centres first; then extra jittered samples only
    // where a pixel differs from a 4-neighbour by more than the threshold.
    renderInBands(frame, win, 1, 1.0f, progress);
    // Only the output window's pixels are refined; the ring around it (film_window_) holds
    // the centres of their neighbours outside it.
    std::vector<int> refine;
    auto differs = [&](int p, int q) {
      glm::vec3 d = glm::abs(radiance_[p] - radiance_[q]);
      return std::max({d.x, d.y, d.z}) > settings_.aa_threshold;
    };
    const PixelWindow& out = output_window_;
    for (int y = out.y0 - win.y0; y < out.y1 - win.y0; ++y)
      for (int x = out.x0 - win.x0, p = y * fw + x; x < out.x1 - win.x0; ++x, ++p)
        if ((x > 0 && differs(p, p - 1)) || (x + 1 < fw && differs(p, p + 1)) ||
            (y > 0 && differs(p, p - fw)) || (y + 1 < fh && differs(p, p + fw)))
          refine.push_back(p);
    const int extra = std::max(1, settings_.aa_samples);
    const float keep = 1.0f / float(extra + 1);
    for (int p : refine) radiance_[p] *= keep;  // the centre becomes one of extra+1 samples
    frame.refined_pixels = refine.size();
    // The refined pixels in passes of at most max_pass_rays samples (at least one pixel).
    const size_t per_pass = std::max<size_t>(1, settings_.max_pass_rays / size_t(extra));
    const size_t passes = (refine.size() + per_pass - 1) / per_pass;
    for (size_t k = 0; k < passes; ++k) {
      const size_t first = k * per_pass, last = std::min(refine.size(), first + per_pass);
      window_pixels_.assign(refine.begin() + first, refine.begin() + last);
      window_pixels_width_ = 0;  // not a band
      renderPass(frame, extra, 1, keep, nullptr, passProgress(progress, int(k), int(passes)));
    }
  }

  frame.film.width = fw;
  frame.film.height = fh;
  frame.film.background = settings_.background;
  frame.film.rgb.resize(pixels * 3);
  parallelFor(0LL, (long long)(pixels), [&](long long p) {
    for (int c = 0; c < 3; ++c) frame.film.rgb[3 * p + c] = radiance_[p][c];
  });
  if (settings_.want_alpha)
    frame.film.alpha = coverage_.alpha();
  else
    frame.film.alpha.clear();
  if (output_window_ != win) {  // the ring of adaptive AA's neighbours is not output
    const PixelWindow& out = output_window_;
    keepWindow(frame.film.rgb, win, out, 3);
    keepWindow(frame.film.alpha, win, out, 1);
    frame.film.width = out.width();
    frame.film.height = out.height();
    PrimaryAovs& a = frame.aovs;
    for (std::vector<float>* one : {&a.depth, &a.tests, &a.list_length})
      keepWindow(*one, win, out, 1);
    for (std::vector<int32_t>* ids : {&a.primid, &a.pe}) keepWindow(*ids, win, out, 1);
    for (std::vector<float>* three : {&a.normal, &a.shading_normal, &a.albedo})
      keepWindow(*three, win, out, 3);
  }
  frame.times.frame_ms = frame_clock.ms();
}

std::function<void(int, int)> Renderer::passProgress(const std::function<void(int, int)>& progress,
                                                     int pass, int passes) {
  if (!progress) return {};
  return [&progress, pass, passes](int done, int total) {
    progress(pass * total + done, passes * total);
  };
}

void Renderer::renderInBands(Frame& frame, const PixelWindow& window, int spp, float weight,
                             const std::function<void(int, int)>& progress) {
  const size_t budget = std::min(settings_.max_pass_rays, kMaxBatchRays);
  const size_t row_rays = size_t(window.width()) * size_t(spp);
  // As few bands as fit the budget, of about equal height (so their buffers fit each other).
  const int most_rows = int(std::clamp<size_t>(budget / row_rays, 1, size_t(window.height())));
  const int bands = (window.height() + most_rows - 1) / most_rows;
  const int rows = (window.height() + bands - 1) / bands;
  for (int band = 0; band < bands; ++band) {
    const PixelWindow part{window.x0, window.y0 + band * rows, window.x1,
                           std::min(window.y1, window.y0 + (band + 1) * rows)};
    if (window_pixels_width_ != settings_.width || window_pixels_band_ != part) {
      window_pixels_.resize(size_t(part.width()) * part.height());
      parallelFor(int(part.y0), int(part.y1), [&](int y) {
        for (int x = part.x0; x < part.x1; ++x)
          window_pixels_[size_t(y - part.y0) * part.width() + (x - part.x0)] =
              (y - film_window_.y0) * film_window_.width() + (x - film_window_.x0);
      });
      window_pixels_band_ = part;
      window_pixels_width_ = settings_.width;
    }
    renderPass(frame, spp, 0, weight, &part, passProgress(progress, band, bands));
  }
}

void Renderer::renderPass(Frame& frame, int spp, int first_sample, float weight,
                          const PixelWindow* window,
                          const std::function<void(int, int)>& progress) {
  Stopwatch clock;
  ++frame.passes;
  const int w = settings_.width, h = settings_.height;
  const size_t rendered = window_pixels_.size();
  // Primary rays: pixel-major, spp samples each (the pixel centre for a lone sample 0).
  // Their own buffers keep their size from frame to frame (no refill with zeros).
  resizeFaultedIn(primary_rays_, rendered * spp);
  const CameraRayGenerator camera_rays(camera_, w, h);
  const bool centre_only = spp == 1 && first_sample == 0;
  // A pinhole camera's pixel centres over a window go through tracePrimary (below), whose
  // intersector makes them (Intersector::generateAndIntersectPrimary).
  const bool traced_primary = window && centre_only && !camera_.orthographic;
  if (traced_primary) {
    // made in tracePrimary
  } else if (centre_only && window) {  // the window's pixel centres, row by row
    camera_rays.centreWindow(*window, primary_rays_.data());
  } else {
    parallelFor(0LL, (long long)(rendered), [&](long long k) {
      const int f = window_pixels_[k], fw = film_window_.width();
      const int x = film_window_.x0 + f % fw, y = film_window_.y0 + f / fw;
      const uint32_t p =
          uint32_t(y) * uint32_t(w) + uint32_t(x);  // the jitter's key: the image's pixel
      for (int s = 0; s < spp; ++s) {
        float sx = 0.5f, sy = 0.5f;
        if (!centre_only) jitter(p, uint32_t(first_sample + s), sx, sy);
        size_t r = size_t(k) * spp + s;
        primary_rays_[r] = camera_rays(x, y, sx, sy);
      }
    });
  }
  frame.times.generate_ms += clock.ms();

  // AOVs come from the first pass (window given), sample 0 of each pixel.
  const bool aov_pass = window != nullptr;
  RayDiagnostics diagnostics;
  // The generations, then the shadow rays of all of them.
  const int total_stages = (settings_.primary_only ? 1 : settings_.max_depth + 1) + 1;
  // The generation being traced: the primary rays (their paths implicit: sample s of
  // window pixel k is ray k * spp + s), then the rays each one spawns.
  const std::vector<GrRay>* rays = &primary_rays_;
  const std::vector<PathRay>* paths = nullptr;
  // A full window pass that spawns rays shades its pixels in 4x4 blocks; the adaptive
  // pass (scattered pixels) in the order of its list, and primary-only shading in ray
  // order (it spawns nothing, and reads and writes its arrays in order).
  const int* order = nullptr;
  if (window && !settings_.primary_only) {
    if (block_order_width_ != window->width() || block_order_height_ != window->height()) {
      pixelBlockOrder(window->width(), window->height(), block_order_);
      block_order_width_ = window->width();
      block_order_height_ = window->height();
    }
    order = block_order_.data();
  }
  const PrimaryPaths primary{spp, weight, order};
  // Every depth's arrays exist before the loop: pointers into them stay valid.
  if (generations_.size() < size_t(settings_.max_depth) + 2)
    generations_.resize(settings_.max_depth + 2);
  size_t shadow_total = 0;
  int depths = 0;
  for (int depth = 0; !rays->empty() && depth <= settings_.max_depth; ++depth) {
    bool first = depth == 0;
    if (first) {
      frame.rays.primary += rays->size();
    } else {
      for (const PathRay& path : *paths)
        if (path.kind == RayKind::Reflection)
          ++frame.rays.reflection;
        else
          ++frame.rays.refraction;
    }
    RayDiagnostics* diag = first && aov_pass && settings_.want_diagnostics ? &diagnostics : nullptr;
    std::vector<GrHit>& hits = generations_[depth].hits;
    double& trace_ms = first ? frame.times.primary_ms : frame.times.secondary_ms;
    if (first && traced_primary)
      tracePrimary(*window, hits, diag, trace_ms);
    else
      traceBatched(*rays, HitMode::Closest, hits, diag, trace_ms);
    frame.rays.see_through += see_through_.passHoles(
        *rays, hits, [&](const std::vector<GrRay>& onward, std::vector<GrHit>& onward_hits) {
          traceBatched(onward, HitMode::Closest, onward_hits, nullptr, trace_ms);
        });
    if (first && aov_pass && (settings_.want_aovs || settings_.want_diagnostics))
      fillPrimaryAovs(frame.aovs, *rays, hits, diagnostics, spp);
    if (first && settings_.want_alpha) countCoverage(hits, spp);
    shadow_total += shadeGeneration(depth, *rays, paths, primary, shadow_total, frame);
    depths = depth + 1;
    rays = &generations_[depth + 1].rays;
    paths = &generations_[depth + 1].paths;
    if (progress) progress(depth + 1, total_stages);
    if (settings_.primary_only) break;
  }

  // The shadow rays of every depth in one batch (any hit before the light means it is
  // occluded), then the pass's light into the pixels.
  resizeFaultedIn(shadow_rays_, shadow_total);
  resizeFaultedIn(shadows_, shadow_total);
  frame.rays.shadow += shadow_total;
  if (shadow_total) traceShadows(frame.times.shadow_ms, frame.rays.see_through);
  clock.restart();
  addPassRadiance(depths, primary);
  frame.times.shade_ms += clock.ms();
  if (progress) progress(total_stages, total_stages);
}

void Renderer::addPassRadiance(int depths, PrimaryPaths primary) {
  for (int depth = 0; depth < depths; ++depth) {
    const Generation& g = generations_[depth];
    const std::vector<glm::vec3>& local = g.radiance;
    if (depth > 0) {
      const std::vector<PathRay>& ps = g.paths;
      addInPixelRuns(
          ps.size(), [&](size_t i) { return ps[i].pixel; },
          [&](size_t i) { radiance_[ps[i].pixel] += local[i]; });
    } else if (!g.radiance_in_pixels) {
      // Primary rays: each pixel's samples are consecutive, pixels distinct.
      parallelFor(0LL, (long long)((local.size() / primary.spp)), [&](long long k) {
        for (int s = 0; s < primary.spp; ++s)
          radiance_[window_pixels_[k]] += local[size_t(k) * primary.spp + s];
      });
    }
    const ShadowRay* shadows = shadows_.data() + g.first_shadow;
    const GrHit* hits = shadow_hits_.data() + g.first_shadow;
    addInPixelRuns(
        g.shadow_count, [&](size_t k) { return shadows[k].pixel; },
        [&](size_t k) {
          if (hits[k].prim < 0) radiance_[shadows[k].pixel] += shadows[k].radiance;
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

Renderer::PrimarySurface Renderer::primarySurface(const GrHit& hit, const GrRay& ray,
                                                  const ShadingTriangle* smooth_triangles) const {
  const HitSurface h = surfaceOfHit(smooth_triangles, geometric_normals_.data(), hit.prim, ray.ox,
                                    ray.oy, ray.oz, ray.dx, ray.dy, ray.dz, hit.t);
  const int material = scene_.material_of[hit.prim];
  const glm::vec3 d(ray.dx, ray.dy, ray.dz);
  const glm::vec3 n = mappedNormal(h, hit, d, cone_origin_);
  const glm::vec3 base = surface_textures_.varies(material)
                             ? surface_textures_
                                   .at(hit.prim, glm::vec3(h.px, h.py, h.pz),
                                       coneWidth(cone_origin_, hit.t), glm::dot(n, d))
                                   .base_color
                             : scene_.materials[material].base_color;
  return {n, base};
}

glm::vec3 Renderer::mappedNormal(const HitSurface& h, const GrHit& hit, const glm::vec3& d,
                                 float cone) const {
  const glm::vec3 n(h.nx, h.ny, h.nz);
  if (!surface_textures_.hasNormalMap(scene_.material_of[hit.prim])) return n;
  return surface_textures_.mappedNormal(hit.prim, glm::vec3(h.px, h.py, h.pz), n, h.backface,
                                        coneWidth(cone, hit.t), glm::dot(n, d));
}

void Renderer::applyNormalMap(SurfaceLanes& lanes, int k, float cone) const {
  const glm::vec3 n(lanes.nx[k], lanes.ny[k], lanes.nz[k]);
  const glm::vec3 d(lanes.dx[k], lanes.dy[k], lanes.dz[k]);
  const glm::vec3 mapped = surface_textures_.mappedNormal(
      lanes.tri[k], glm::vec3(lanes.px[k], lanes.py[k], lanes.pz[k]), n, lanes.backface[k] != 0,
      coneWidth(cone, lanes.t[k]), glm::dot(n, d));
  lanes.nx[k] = mapped.x, lanes.ny[k] = mapped.y, lanes.nz[k] = mapped.z;
}

bool Renderer::worthTracing(const glm::vec3& weight) const {
  return std::max({weight.x, weight.y, weight.z}) >= settings_.min_path_weight;
}

size_t Renderer::shadeGeneration(int depth, const std::vector<GrRay>& rays,
                                 const std::vector<PathRay>* paths, PrimaryPaths primary,
                                 size_t shadow_offset, Frame& frame) {
  return settings_.primary_only ? shadeHeadlight(depth, rays, primary, shadow_offset, frame)
                                : shadeWhitted(depth, rays, paths, primary, shadow_offset, frame);
}

size_t Renderer::shadeHeadlight(int depth, const std::vector<GrRay>& rays, PrimaryPaths primary,
                                size_t shadow_offset, Frame& frame) {
  Stopwatch clock;
  const size_t n = rays.size();
  Generation& g = generations_[depth];
  resizeFaultedIn(g.radiance, n);
  std::vector<glm::vec3>& local = g.radiance;
  // Null without vertex normals (hit_surfaces.h).
  const ShadingTriangle* smooth_triangles =
      shading_triangles_.empty() ? nullptr : shading_triangles_.data();
  // The primary generation only, in ray order. One plain loop: the Whitted loop's per-ray
  // bookkeeping (paths, shading order, blocks of 16) cost more than this shading does.
  // With one sample a pixel (pixels distinct, in ray order), each ray's radiance goes
  // straight into its pixel: the same addition addPassRadiance would make, a pass less.
  const glm::vec3 weight(primary.weight);
  const bool into_pixels = primary.spp == 1;
  g.radiance_in_pixels = into_pixels;
  parallelFor(0LL, (long long)(n), [&](long long i) {
    const GrHit& hit = g.hits[i];
    glm::vec3 value;
    if (hit.prim < 0) {
      value = weight * settings_.background;
    } else {
      const GrRay& ray = rays[i];
      const PrimarySurface surface = primarySurface(hit, ray, smooth_triangles);
      value = weight * surface.base_color *
              std::fabs(glm::dot(surface.normal, glm::vec3(ray.dx, ray.dy, ray.dz)));
    }
    if (into_pixels)
      radiance_[window_pixels_[i]] += value;
    else
      local[i] = value;
  });
  frame.times.shade_ms += clock.ms();
  g.first_shadow = shadow_offset;
  g.shadow_count = 0;
  generations_[depth + 1].rays.clear();
  generations_[depth + 1].paths.clear();
  return 0;
}

size_t Renderer::shadeWhitted(int depth, const std::vector<GrRay>& rays,
                              const std::vector<PathRay>* paths, PrimaryPaths primary,
                              size_t shadow_offset, Frame& frame) {
  Stopwatch clock;
  const size_t n = rays.size();
  // Each chunk writes its own outputs (Spawned), which keeps the parallel loop free of
  // shared appends; they are concatenated afterwards in chunk order, the shading order.
  Generation& g = generations_[depth];
  resizeFaultedIn(g.radiance, n);
  std::vector<glm::vec3>& local = g.radiance;
  // Null without vertex normals (hit_surfaces.h).
  const ShadingTriangle* smooth_triangles =
      shading_triangles_.empty() ? nullptr : shading_triangles_.data();
  g.radiance_in_pixels = false;
  const bool spawn = depth < settings_.max_depth;
  // Chunks handed out dynamically: the rays' cost varies across the image (background,
  // walls, mirror and glass), so a static split leaves one core waiting.
  const size_t chunks = (n + kShadeChunkRays - 1) / kShadeChunkRays;
  if (spawned_.size() < chunks) spawned_.resize(chunks);

  parallelForDynamic(0LL, (long long)(chunks), 1LL, [&](long long chunk) {
    Spawned& out = spawned_[chunk];
    out.shadow_count = 0;
    out.ray_count = 0;
    out.light_lanes.resize(lights_.size());
    SurfaceLanes lanes;
    // The plain path (plain_shading.h) needs the highlights of Phong shading.
    const bool plain_path = settings_.plain_lanes && settings_.shading == ShadingModel::Phong;
    if (plain_path) out.plain_light_lanes.resize(lights_.size());
    PlainLanes plain;
    SpawnLanes spawned;
    const size_t chunk_begin = size_t(chunk) * kShadeChunkRays;
    const size_t chunk_end = std::min(n, chunk_begin + kShadeChunkRays);
    // The primary generation in its shading order: sample `sample` of the pixel at
    // `position` of the order (j / spp and j % spp, counted along instead of divided).
    const size_t spp = size_t(primary.spp);
    size_t position = chunk_begin / spp, sample = chunk_begin % spp;
    // The hits in blocks of 16 (a miss is done at once): their surfaces and light
    // directions in lanes, then each hit's shading in order.
    size_t block_ray[kSurfaceLanes];
    PathRay block_path[kSurfaceLanes];
    for (size_t j = chunk_begin; j < chunk_end;) {
      int count = 0;
      for (; count < kSurfaceLanes && j < chunk_end; ++j) {
        const size_t pixel_index = paths           ? 0
                                   : primary.order ? size_t(primary.order[position])
                                                   : position;
        const size_t i = paths || !primary.order ? j : pixel_index * spp + sample;
        sample = sample + 1 == spp ? 0 : sample + 1;
        position += sample == 0;
        const GrHit& hit = g.hits[i];
        if (hit.prim < 0) {
          local[i] =
              (paths ? (*paths)[i].weight : glm::vec3(primary.weight)) * settings_.background;
          continue;
        }
        const GrRay& ray = rays[i];
        const int k = count++;
        block_ray[k] = i;
        // Field by field: a path built in a temporary and copied out (a 16-byte load of
        // narrower stores, a store-forwarding stall) held 8 % of the shading's samples.
        PathRay& path = block_path[k];
        if (paths) {
          path = (*paths)[i];
        } else {
          path.pixel = window_pixels_[pixel_index];
          path.weight = glm::vec3(primary.weight);
          path.kind = RayKind::Primary;
          path.cone = cone_origin_;
        }
        lanes.ox[k] = ray.ox, lanes.oy[k] = ray.oy, lanes.oz[k] = ray.oz;
        lanes.dx[k] = ray.dx, lanes.dy[k] = ray.dy, lanes.dz[k] = ray.dz;
        lanes.t[k] = hit.t;
        lanes.tri[k] = hit.prim;
      }
      if (count == 0) continue;
      for (int k = count; k < kSurfaceLanes; ++k) {  // a block's last lanes: copies of lane 0
        lanes.ox[k] = lanes.ox[0], lanes.oy[k] = lanes.oy[0], lanes.oz[k] = lanes.oz[0];
        lanes.dx[k] = lanes.dx[0], lanes.dy[k] = lanes.dy[0], lanes.dz[k] = lanes.dz[0];
        lanes.t[k] = lanes.t[0], lanes.tri[k] = lanes.tri[0];
      }
      computeSurfaces(smooth_triangles, geometric_normals_.data(), lanes);
      for (int k = 0; k < count; ++k)  // normal maps turn the shading normal before the lights
        if (surface_textures_.hasNormalMap(scene_.material_of[lanes.tri[k]]))
          applyNormalMap(lanes, k, block_path[k].cone);
      for (size_t l = 0; l < lights_.size(); ++l)
        computeLightLanes(lights_[l], lanes, out.light_lanes[l]);
      if (settings_.shading == ShadingModel::Phong) {
        // The highlights for each material's own exponent; a textured one's is made below.
        alignas(64) float exponent[kSurfaceLanes];
        for (int k = 0; k < kSurfaceLanes; ++k)
          exponent[k] = material_terms_[scene_.material_of[lanes.tri[k]]].phong_exponent;
        for (size_t l = 0; l < lights_.size(); ++l)
          computeHighlights(lanes, exponent, out.light_lanes[l]);
      }
      bool spawning = false;  // a plain lane of the block mirrors or transmits
      if (plain_path) {
        for (int k = 0; k < kSurfaceLanes; ++k) {
          const glm::vec3& w = block_path[k < count ? k : 0].weight;
          plain.wr[k] = w.x, plain.wg[k] = w.y, plain.wb[k] = w.z;
          plain.material[k] = scene_.material_of[lanes.tri[k]];
          spawning |= plain_materials_[plain.material[k]].spawning != 0;
        }
        computePlainLanes(lanes, plain_materials_.data(), settings_.ambient, settings_.ray_offset,
                          plain);
        spawning &= spawn;
        if (spawning)
          computeSpawnLanes(lanes, plain_materials_.data(), settings_.ray_offset,
                            settings_.min_path_weight, plain, spawned);
        for (size_t l = 0; l < lights_.size(); ++l)
          computePlainLight(plain, plain_materials_.data(), out.light_lanes[l],
                            out.plain_light_lanes[l]);
      }
      for (int k = 0; k < count; ++k) {
        const size_t i = block_ray[k];
        const PathRay& path = block_path[k];
        if (plain_path && plain.plain[k]) {
          local[i] = glm::vec3(plain.lr[k], plain.lg[k], plain.lb[k]);
          for (size_t l = 0; l < lights_.size(); ++l) {
            const PlainLightLanes& c = out.plain_light_lanes[l];
            if (!c.emit[k]) continue;
            const LightLanes& light = out.light_lanes[l];
            const size_t s = nextSlot(out.shadow_rays, out.shadows, out.shadow_count);
            out.shadow_rays[s] = makeRay(glm::vec3(plain.ax[k], plain.ay[k], plain.az[k]),
                                         glm::vec3(light.lx[k], light.ly[k], light.lz[k]),
                                         light.distance[k], plain.offset[k]);
            out.shadows[s] = ShadowRay{path.pixel, int(l), glm::vec3(c.cr[k], c.cg[k], c.cb[k])};
          }
          if (!spawning) continue;
          const float cone = coneWidth(path.cone, lanes.t[k]);
          auto spawnRay = [&](float ox, float oy, float oz, float dx, float dy, float dz, float wr,
                              float wg, float wb, RayKind kind) {
            const size_t s = nextSlot(out.rays, out.paths, out.ray_count);
            out.rays[s] = makeRay(glm::vec3(ox, oy, oz), glm::vec3(dx, dy, dz), kInf);
            out.paths[s] = PathRay{path.pixel, glm::vec3(wr, wg, wb), kind, cone};
          };
          const SpawnLanes& o = spawned;  // the refraction ray first, as below
          if (o.refract[k])
            spawnRay(o.rox[k], o.roy[k], o.roz[k], o.rdx[k], o.rdy[k], o.rdz[k], o.rwr[k], o.rwg[k],
                     o.rwb[k], RayKind::Refraction);
          if (o.reflect[k])
            spawnRay(plain.ax[k], plain.ay[k], plain.az[k], o.fdx[k], o.fdy[k], o.fdz[k], o.fwr[k],
                     o.fwg[k], o.fwb[k], RayKind::Reflection);
          continue;
        }
        const GrHit& hit = g.hits[i];
        glm::vec3 d(lanes.dx[k], lanes.dy[k], lanes.dz[k]);
        const int tri = hit.prim;
        const int material = scene_.material_of[tri];
        const Material& mat = scene_.materials[material];
        glm::vec3 weight = path.weight;
        const glm::vec3 p(lanes.px[k], lanes.py[k], lanes.pz[k]);
        const glm::vec3 ng(lanes.gx[k], lanes.gy[k], lanes.gz[k]);
        const glm::vec3 n(lanes.nx[k], lanes.ny[k], lanes.nz[k]);
        const bool backface = lanes.backface[k];
        // Textures and vertex colours: the material's values at this hit.
        const float cone = coneWidth(path.cone, hit.t);
        SurfaceTerms terms = material_terms_[material];
        glm::vec3 base_color = mat.base_color, emissive = mat.emissive;
        float metallic = mat.metallic, roughness = mat.roughness;
        float ambient = settings_.ambient;
        if (surface_textures_.varies(material)) {
          const MaterialSample here = surface_textures_.at(tri, p, cone, glm::dot(n, d));
          terms = surfaceTerms(mat, here.base_color, here.metallic, here.roughness);
          base_color = here.base_color;
          metallic = here.metallic;
          roughness = here.roughness;
          emissive = here.emissive;
          ambient *= here.occlusion;
        }
        // Beer-Lambert absorption inside a transmissive volume (KHR_materials_volume).
        if (backface && mat.transmission > 0.0f && mat.attenuation_distance > 0.0f)
          weight *= glm::pow(glm::max(mat.attenuation_color, glm::vec3(1e-6f)),
                             glm::vec3(hit.t / mat.attenuation_distance));
        // BLEND: the alpha's share of the light is the surface's, the rest goes on along
        // the ray (from the same origin past this hit) as a straight transmission.
        if (mat.alpha_mode == AlphaMode::Blend) {
          const float coverage = see_through_.coverage(rays[i], hit);
          const glm::vec3 through = weight * (1.0f - coverage);
          if (spawn && coverage < 1.0f && worthTracing(through)) {
            const size_t s = nextSlot(out.rays, out.paths, out.ray_count);
            out.rays[s] = rays[i];
            out.rays[s].tmin = hit.t;
            out.paths[s] = PathRay{path.pixel, through, RayKind::Refraction, path.cone};
          }
          weight *= coverage;
        }
        local[i] = weight * (emissive + ambient * terms.diffuse);
        const glm::vec3 origin(lanes.ox[k], lanes.oy[k], lanes.oz[k]);
        // How far secondary origins leave the surface, and where shadow rays start.
        const float offset_distance = rayOffsetDistance(p, origin, settings_.ray_offset);
        glm::vec3 above = offsetRayOrigin(p, ng, offset_distance, settings_.ray_offset);
        for (size_t l = 0; l < lights_.size(); ++l) {
          const LightLanes& light = out.light_lanes[l];
          if (!light.lit[k]) continue;
          const glm::vec3 to_light(light.lx[k], light.ly[k], light.lz[k]);
          const glm::vec3 e(light.ex[k], light.ey[k], light.ez[k]);
          const float cos_theta = light.cos_theta[k];
          glm::vec3 direct;
          if (settings_.shading == ShadingModel::Gltf) {
            direct = gltfBrdf(base_color, metallic, roughness, n, -d, to_light, mat.transmission) *
                     e * cos_theta;
          } else {
            const float highlight = surface_textures_.varies(material)
                                        ? phongHighlight(light.rv[k], terms.phong_exponent)
                                        : light.highlight[k];
            direct = terms.diffuse / kPi * e * cos_theta + terms.specular * e * highlight;
          }
          glm::vec3 contribution = weight * direct;
          // glm::length(c) == 0 without its root (sqrt(x) == 0 exactly when x == 0).
          if (glm::dot(contribution, contribution) == 0.0f) continue;
          const size_t s = nextSlot(out.shadow_rays, out.shadows, out.shadow_count);
          out.shadow_rays[s] = makeRay(above, to_light, light.distance[k], offset_distance);
          out.shadows[s] = ShadowRay{path.pixel, int(l), contribution};
        }
        if (!spawn) continue;
        glm::vec3 reflect_weight = terms.mirror;
        if (terms.transmission > 0.0f) {
          float eta = backface ? mat.ior : 1.0f / mat.ior;
          float f = fresnelDielectric(-glm::dot(d, n), eta);
          glm::vec3 t_dir;
          glm::vec3 t_weight = weight * terms.transmission * (1.0f - f) * base_color;
          if (f < 1.0f && refractDirection(d, n, eta, t_dir) && glm::dot(t_dir, ng) < 0.0f) {
            if (worthTracing(t_weight)) {
              const size_t s = nextSlot(out.rays, out.paths, out.ray_count);
              out.rays[s] = makeRay(offsetRayOrigin(p, -ng, offset_distance, settings_.ray_offset),
                                    t_dir, kInf);
              out.paths[s] = PathRay{path.pixel, t_weight, RayKind::Refraction, cone};
            }
          } else {
            f = 1.0f;  // total internal reflection
          }
          reflect_weight += glm::vec3(terms.transmission * f);
        }
        if (glm::dot(reflect_weight, reflect_weight) > 0.0f &&
            worthTracing(weight * reflect_weight)) {
          glm::vec3 r = reflectDirection(d, n);
          if (glm::dot(r, ng) <= 0.0f) r = reflectDirection(d, ng);  // keep it above the surface
          const size_t s = nextSlot(out.rays, out.paths, out.ray_count);
          out.rays[s] = makeRay(above, r, kInf);
          out.paths[s] = PathRay{path.pixel, weight * reflect_weight, RayKind::Reflection, cone};
        }
      }
    }
  });
  frame.times.shade_ms += clock.ms();

  // The shadow rays after the earlier depths' (traced after the last depth).
  g.first_shadow = shadow_offset;
  g.shadow_count = concatenateChunks(chunks, &Spawned::shadow_rays, &Spawned::shadows,
                                     &Spawned::shadow_count, shadow_rays_, shadows_, shadow_offset);

  // The next generation: the spawned reflection and refraction rays, in chunk order.
  Generation& next = generations_[depth + 1];
  const size_t spawned = concatenateChunks(chunks, &Spawned::rays, &Spawned::paths,
                                           &Spawned::ray_count, next.rays, next.paths, 0);
  next.rays.resize(spawned);
  next.paths.resize(spawned);
  return g.shadow_count;
}

template <typename Extra>
size_t Renderer::concatenateChunks(size_t chunks, std::vector<GrRay> Spawned::*rays,
                                   std::vector<Extra> Spawned::*extras, size_t Spawned::*count,
                                   std::vector<GrRay>& all_rays, std::vector<Extra>& all_extras,
                                   size_t offset) {
  chunk_offsets_.assign(chunks + 1, offset);
  for (size_t c = 0; c < chunks; ++c)
    chunk_offsets_[c + 1] = chunk_offsets_[c] + spawned_[c].*count;
  if (all_rays.size() < chunk_offsets_[chunks]) resizeFaultedIn(all_rays, chunk_offsets_[chunks]);
  if (all_extras.size() < chunk_offsets_[chunks])
    resizeFaultedIn(all_extras, chunk_offsets_[chunks]);
  parallelFor(0LL, (long long)(chunks), [&](long long c) {
    const Spawned& out = spawned_[c];
    std::copy_n((out.*rays).begin(), out.*count, all_rays.begin() + chunk_offsets_[c]);
    std::copy_n((out.*extras).begin(), out.*count, all_extras.begin() + chunk_offsets_[c]);
  });
  return chunk_offsets_[chunks] - offset;
}

}  // namespace gridrt
