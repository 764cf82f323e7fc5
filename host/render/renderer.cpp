// The frame and its waves: the film cleared, the image's rows in waves of at most
// max_pass_rays camera rays (renderInBands), each wave's generations traced, shaded and
// spawned in turn (renderPass), adaptive refinement, the film filled.
#include "renderer.h"

#include <algorithm>
#include <cmath>

#include "camera_rays.h"
#include "default_lighting.h"
#include "parallel_loops.h"
#include "pixel_blocks.h"
#include "prefault.h"
#include "stopwatch.h"

namespace gridrt {

namespace {

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
  radiance_.clear(pixels);
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

  if (settings_.single_sample >= 0) {
    renderInBands(frame, win, 1, settings_.single_sample, 1.0f, progress);
  } else if (!settings_.adaptive_aa) {
    const int spp = std::max(1, settings_.spp);
    renderInBands(frame, win, spp, spp == 1 ? -1 : 0, 1.0f / float(spp), progress);
  } else {
    // Adaptive supersampling: the pixel centres first; then extra jittered samples only
    // where a pixel differs from a 4-neighbour by more than the threshold.
    renderInBands(frame, win, 1, -1, 1.0f, progress);
    // Only the output window's pixels are refined; the ring around it (film_window_) holds
    // the centres of their neighbours outside it.
    auto differs = [&](int p, int q) {
      glm::vec3 d = glm::abs(radiance_.at(p) - radiance_.at(q));
      return std::max({d.x, d.y, d.z}) > settings_.aa_threshold;
    };
    // Each slice lists the pixels of its rows, and the lists follow one another in row
    // order: the same list as one thread's.
    const PixelWindow& out = output_window_;
    const int slices = parallelSliceCount();
    std::vector<std::vector<int>> slice_refine(slices);
    parallelSlices(slices, [&](int me, int count) {
      const auto [first, last] = sliceRange(size_t(out.height()), me, count);
      for (int y = out.y0 - win.y0 + int(first); y < out.y0 - win.y0 + int(last); ++y)
        for (int x = out.x0 - win.x0, p = y * fw + x; x < out.x1 - win.x0; ++x, ++p)
          if ((x > 0 && differs(p, p - 1)) || (x + 1 < fw && differs(p, p + 1)) ||
              (y > 0 && differs(p, p - fw)) || (y + 1 < fh && differs(p, p + fw)))
            slice_refine[me].push_back(p);
    });
    std::vector<int> refine;
    for (const std::vector<int>& part : slice_refine)
      refine.insert(refine.end(), part.begin(), part.end());
    const int extra = std::max(1, settings_.aa_samples);
    const float keep = 1.0f / float(extra + 1);
    // The centre becomes one of extra+1 samples (after every slice has read its neighbours).
    parallelFor(size_t(0), refine.size(), [&](size_t k) { radiance_.scale(refine[k], keep); });
    frame.refined_pixels = refine.size();
    // The refined pixels in passes of at most max_pass_rays samples (at least one pixel).
    const size_t per_pass = std::max<size_t>(1, settings_.max_pass_rays / size_t(extra));
    const size_t passes = (refine.size() + per_pass - 1) / per_pass;
    for (size_t k = 0; k < passes; ++k) {
      const size_t first = k * per_pass, last = std::min(refine.size(), first + per_pass);
      window_pixels_.assign(refine.begin() + first, refine.begin() + last);
      renderPass(frame, extra, 1, keep, nullptr, passProgress(progress, int(k), int(passes)));
    }
  }

  frame.film.width = fw;
  frame.film.height = fh;
  frame.film.background = settings_.background;
  radiance_.moveInto(frame.film.rgb);
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

void Renderer::renderInBands(Frame& frame, const PixelWindow& window, int spp, int first_sample,
                             float weight, const std::function<void(int, int)>& progress) {
  const size_t budget = std::min(settings_.max_pass_rays, kMaxBatchRays);
  const size_t row_rays = size_t(window.width()) * size_t(spp);
  // As few bands as fit the budget, of about equal height (so their buffers fit each other).
  const int most_rows = int(std::clamp<size_t>(budget / row_rays, 1, size_t(window.height())));
  const int bands = (window.height() + most_rows - 1) / most_rows;
  const int rows = (window.height() + bands - 1) / bands;
  for (int band = 0; band < bands; ++band) {
    const PixelWindow part{window.x0, window.y0 + band * rows, window.x1,
                           std::min(window.y1, window.y0 + (band + 1) * rows)};
    if (band_pixels_.size() < size_t(bands)) band_pixels_.resize(bands);
    BandPixels& kept = band_pixels_[band];
    if (kept.image_width != settings_.width || kept.band != part) {
      kept.pixels.resize(size_t(part.width()) * part.height());
      parallelFor(int(part.y0), int(part.y1), [&](int y) {
        for (int x = part.x0; x < part.x1; ++x)
          kept.pixels[size_t(y - part.y0) * part.width() + (x - part.x0)] =
              (y - film_window_.y0) * film_window_.width() + (x - film_window_.x0);
      });
      kept.band = part;
      kept.image_width = settings_.width;
    }
    // The band's pixels lent to window_pixels_ for its pass, and kept for the next frame.
    window_pixels_.swap(kept.pixels);
    renderPass(frame, spp, first_sample, weight, &part, passProgress(progress, band, bands));
    window_pixels_.swap(kept.pixels);
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
  const bool centre_only = first_sample < 0;
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
      std::vector<uint64_t> slice_reflections(parallelSliceCount(), 0);
      parallelSlices(int(slice_reflections.size()), [&](int me, int count) {
        const auto [first, last] = sliceRange(paths->size(), me, count);
        uint64_t reflections = 0;
        for (size_t k = first; k < last; ++k)
          reflections += (*paths)[k].kind == RayKind::Reflection;
        slice_reflections[me] = reflections;
      });
      uint64_t reflections = 0;
      for (uint64_t r : slice_reflections) reflections += r;
      frame.rays.reflection += reflections;
      frame.rays.refraction += paths->size() - reflections;
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

}  // namespace gridrt
