// The Whitted renderer: a wavefront loop on the host. Generate a batch of rays, have the
// intersector find their hits on the device, shade on the host (all cores), spawn the
// next batch (reflection and refraction) and shadow rays per light, until max depth.
// Nothing later depends on a shadow ray, so the shadow rays of all depths are traced in
// one batch at the end of the pass, and only then is the light added to the pixels. A
// large frame is rendered in several such passes, bands of whole rows (kMaxPassRays):
// the frame's waves. The loop's rooms: renderer.cpp (the frame and its waves),
// renderer_batches.cpp (rays to the intersector), renderer_shading.cpp (the shading
// passes), renderer_film.cpp (what a wave adds to the film and the AOVs).
#pragma once
#include <array>
#include <functional>
#include <glm/glm.hpp>
#include <vector>

#include "film.h"
#include "gltf_brdf.h"
#include "hit_surfaces.h"
#include "intersector.h"
#include "pixel_radiance.h"
#include "pixel_window.h"
#include "plain_shading.h"
#include "sample_coverage.h"
#include "scene.h"
#include "see_through_hits.h"
#include "surface_textures.h"
#include "whitted_shading.h"

namespace gridrt {

// A frame with more primary rays than this (pixels x samples) is rendered in passes of
// whole rows that reuse one another's buffers: memory follows the pass, not the image
// (a 4K frame took 3.4 GB in one pass). A pixel lies in one pass, so the image is the
// same bit for bit. A row is never split: one row's samples may exceed it.
constexpr size_t kMaxPassRays = size_t(1) << 19;

struct RenderSettings {
  int width = 640;
  int height = 480;
  int spp = 1;                 // samples per pixel: jittered inside the pixel when > 1
  int max_depth = 5;           // reflection/refraction bounces after the primary hit
  bool primary_only = false;   // primary rays with headlight shading (the paper's measurement)
  glm::vec3 background{0.0f};  // colour of rays that miss (black, as in the paper)
  float ambient = 0.05f;       // ambient radiance factor: ambient * diffuse albedo, lit or not
  RayOffset ray_offset;        // how secondary ray origins leave the surface
  ShadingModel shading = ShadingModel::Phong;  // punctual lights: Phong or the glTF BRDF
  bool want_aovs = true;          // fill the depth / primid / normal / albedo AOVs of primary rays
  bool want_diagnostics = false;  // fill tests / PE / list-length AOVs of primary rays
  // Fill Film::alpha: per pixel, the share of its camera samples (all of them: every spp
  // sample, adaptive refinement too) whose ray hit geometry. Off: the film has no alpha.
  bool want_alpha = false;
  PixelWindow crop;  // render only these pixels (the film and AOVs hold the window alone)
  // Adaptive supersampling (--aa adaptive): centres first, then aa_samples jittered samples
  // where a pixel differs from a 4-neighbour by more than aa_threshold (any channel).
  bool adaptive_aa = false;
  int aa_samples = 8;
  float aa_threshold = 0.1f;
  // Adaptive depth: a reflection/refraction ray whose throughput (max channel) is below
  // this is not traced; 0 traces every ray up to max_depth.
  float min_path_weight = 0.0f;
  // >= 0: the frame holds only sample `single_sample` of a frame of spp jittered samples,
  // with weight 1 (the viewer's progressive refinement adds such frames up); -1: all spp
  // samples, each of weight 1/spp. Uniform sampling only (not with adaptive_aa).
  int single_sample = -1;
  // Primary rays per pass (kMaxPassRays unless a test wants small passes).
  size_t max_pass_rays = kMaxPassRays;
  // Hits on plain surfaces shaded 16 at a time (plain_shading.h); off, every hit takes the
  // one-hit loop (the same bits: tests compare the two).
  bool plain_lanes = true;
};

// Rays traced per kind in one frame.
struct RayCounts {
  uint64_t primary = 0, shadow = 0, reflection = 0, refraction = 0;
  // Rays traced again past alphaMode MASK holes and BLEND surfaces (see_through_hits.h).
  uint64_t see_through = 0;
  uint64_t total() const { return primary + shadow + reflection + refraction + see_through; }
};

// Primary-ray AOVs (sample 0 of each pixel).
struct PrimaryAovs {
  std::vector<float> depth;           // t of the primary hit (unit direction), -1 on a miss
  std::vector<int32_t> primid;        // global triangle index, -1 on a miss
  std::vector<float> normal;          // geometric normal (xyz), 0 on a miss
  std::vector<float> shading_normal;  // the normal shading used, facing the ray (xyz), 0 on a miss
  std::vector<float> albedo;          // linear base colour: factor x texture x COLOR_0 (rgb)
  std::vector<float> tests;           // ray-triangle tests of the primary ray
  std::vector<int32_t> pe;            // winning PE, -1 on a miss
  std::vector<float> list_length;     // PEs in the traversal list
};

struct FrameTimes {
  double generate_ms = 0, shade_ms = 0, frame_ms = 0;
  // Tracing, by the kind of ray traced: camera rays, reflection and refraction rays (all
  // bounces), shadow rays.
  double primary_ms = 0, secondary_ms = 0, shadow_ms = 0;
  double intersectMs() const { return primary_ms + secondary_ms + shadow_ms; }
};

struct Frame {
  Film film;  // the crop window's pixels (RenderSettings::crop), or the whole image
  PrimaryAovs aovs;
  RayCounts rays;
  FrameTimes times;
  uint64_t refined_pixels = 0;  // pixels that got extra samples (adaptive supersampling)
  uint64_t passes = 0;          // renderPass calls (bands of rows, then refinement)
};

// Rays at or beyond this count are traced in several batches, bounding device memory.
constexpr size_t kMaxBatchRays = size_t(1) << 21;
static_assert(kMaxPassRays <= kMaxBatchRays, "a pass's camera rays are one batch");
// Rays per chunk of the shading loop (a unit of dynamic scheduling).
constexpr size_t kShadeChunkRays = 2048;

class Renderer {
 public:
  Renderer(const Scene& scene, const Camera& camera, Intersector& intersector,
           RenderSettings settings);
  // Renders one frame. progress(done, total) is called between wavefront stages.
  void render(Frame& frame, const std::function<void(int, int)>& progress = {});
  // Which sample the next frames hold (RenderSettings::single_sample; -1: all of them).
  void setSingleSample(int sample) { settings_.single_sample = sample; }

 private:
  enum class RayKind : uint8_t { Primary, Reflection, Refraction };
  struct PathRay {
    int pixel;
    glm::vec3 weight;  // throughput from the camera to this ray
    RayKind kind;
    float cone = 0.0f;  // the ray cone's width at the ray's origin (texture level of detail)
  };
  struct ShadowRay {
    int pixel;
    int light;           // index into lights_
    glm::vec3 radiance;  // added to the pixel if the shadow ray reaches the light
  };
  // One batch of at most kMaxBatchRays rays: its hits (and diagnostics when asked).
  using BatchTrace =
      std::function<void(const std::vector<GrRay>&, std::vector<GrHit>&, RayDiagnostics*)>;
  // Traces `rays` through `trace` in batches of at most kMaxBatchRays, bounding device
  // memory; hits (and diagnostics) come back in ray order.
  void traceInBatches(const std::vector<GrRay>& rays, std::vector<GrHit>& hits,
                      RayDiagnostics* diagnostics, double& ms, const BatchTrace& trace);
  void traceBatched(const std::vector<GrRay>& rays, HitMode mode, std::vector<GrHit>& hits,
                    RayDiagnostics* diagnostics, double& ms);
  // Traces `spp` primary samples (jitter indices first_sample...; first_sample -1: one
  // sample, the pixel centre) of window_pixels_, each
  // path starting with throughput `weight`, through all bounces into radiance_. `window`
  // (the pixels as a rectangle) marks a pass of whole rows; with sample 0 it writes the
  // AOVs of its pixels.
  void renderPass(Frame& frame, int spp, int first_sample, float weight, const PixelWindow* window,
                  const std::function<void(int, int)>& progress);
  // renderPass over `window` in bands of whole rows of at most max_pass_rays primary rays
  // (at least one row each), window_pixels_ set to each band's pixels.
  // first_sample: the jitter index of each pixel's first sample (-1: spp == 1 at the centre).
  void renderInBands(Frame& frame, const PixelWindow& window, int spp, int first_sample,
                     float weight, const std::function<void(int, int)>& progress);
  // Pass `pass` of `passes`' stages on one progress scale: the passes one after the other.
  static std::function<void(int, int)> passProgress(const std::function<void(int, int)>& progress,
                                                    int pass, int passes);
  bool worthTracing(const glm::vec3& weight) const;
  // The pixel centres of `window` (a pinhole camera, at most one pass of them) made into
  // primary_rays_ and traced by Intersector::generateAndIntersectPrimary; their hits into
  // `hits`.
  void tracePrimary(const PixelWindow& window, std::vector<GrHit>& hits,
                    RayDiagnostics* diagnostics, double& ms);
  // Shades one generation (rays, their paths and generations_[depth].hits): leaves what
  // each ray adds to its pixel in generations_[depth].radiance, appends its shadow rays
  // to shadow_rays_ / shadows_ from `shadow_offset` on (returns how many) and leaves the
  // spawned rays in generations_[depth + 1].rays / paths.
  // The paths of primary rays are implicit: ray k * spp + s is sample s of window pixel
  // k, with throughput `weight`.
  // order (may be null: 0, 1, 2, ...) lists the window pixels in the order they are
  // shaded, which is the order their spawned rays are traced in (pixel_blocks.h).
  struct PrimaryPaths {
    int spp;
    float weight;
    const int* order;
  };
  // paths is null for the primary generation.
  struct Generation;
  // Traces shadow_rays_ into shadow_hits_ (any hit), light by light: rays towards a
  // point or spot light through Intersector::intersectTowardsPoint; then past see-through
  // surfaces (their rays traced again counted into see_through_rays).
  void traceShadows(double& ms, uint64_t& see_through_rays);
  // shadow_rays_ into light_rays_ / light_ray_index_ by light, a stable counting sort on all
  // cores.
  void splitShadowsByLight();
  // Shades generation `depth` (its hits in generations_[depth]): headlight shading with
  // primary_only, Whitted shading otherwise. Returns the shadow rays it spawned.
  size_t shadeGeneration(int depth, const std::vector<GrRay>& rays,
                         const std::vector<PathRay>* paths, PrimaryPaths primary,
                         size_t shadow_offset, Frame& frame);
  // Headlight shading (the paper's measurement) of the primary generation: each hit its
  // base colour times |n . d|; no lights, no spawned rays.
  size_t shadeHeadlight(int depth, const std::vector<GrRay>& rays, PrimaryPaths primary,
                        size_t shadow_offset, Frame& frame);
  // Whitted shading: emission, ambient and direct light (spawning shadow rays), and the
  // reflection and refraction rays of the next generation below max_depth.
  size_t shadeWhitted(int depth, const std::vector<GrRay>& rays, const std::vector<PathRay>* paths,
                      PrimaryPaths primary, size_t shadow_offset, Frame& frame);
  // Adds depths [0, depths) of the pass to radiance_ in the order a depth-by-depth
  // renderer would: each depth's own radiance, then its shadow rays that reached their
  // light (so every pixel's sum is the same, bit for bit).
  void addPassRadiance(int depths, PrimaryPaths primary);
  // Adds the pass's camera samples of window_pixels_ (spp each, their hits in `hits`) to
  // coverage_.
  void countCoverage(const std::vector<GrHit>& hits, int spp);
  // The AOVs of window_pixels_ (the arrays sized for the film by render).
  void fillPrimaryAovs(PrimaryAovs& aovs, const std::vector<GrRay>& rays,
                       const std::vector<GrHit>& hits, const RayDiagnostics& diagnostics, int spp);
  // The shading normal of hit surface h, turned by its material's normal map if it has one
  // (d: the ray's direction; cone: its cone's width at its origin).
  glm::vec3 mappedNormal(const HitSurface& h, const GrHit& hit, const glm::vec3& d,
                         float cone) const;
  // A camera ray's hit: its shading normal (normal-mapped) and base colour (factor times
  // texture times vertex colour), as the AOVs take them (the headlight shading makes the
  // same values 16 hits at a time).
  struct PrimarySurface {
    glm::vec3 normal, base_color;
  };
  PrimarySurface primarySurface(const GrHit& hit, const GrRay& ray,
                                const ShadingTriangle* smooth_triangles) const;
  // The same for lane k of `lanes`, written back into its shading normal.
  void applyNormalMap(SurfaceLanes& lanes, int k, float cone) const;
  // The width of a ray cone that left its origin `cone` wide after distance t.
  float coneWidth(float cone, float t) const { return cone + cone_spread_ * t; }
  struct Spawned;
  // The chunks' rays (and their shadows or paths) one after the other, in chunk order,
  // copied on all cores to all_rays / all_extras from `offset` on (both grown if too
  // short, never shrunk); returns how many.
  template <typename Extra>
  size_t concatenateChunks(size_t chunks, std::vector<GrRay> Spawned::*rays,
                           std::vector<Extra> Spawned::*extras, size_t Spawned::*count,
                           std::vector<GrRay>& all_rays, std::vector<Extra>& all_extras,
                           size_t offset);

  const Scene& scene_;
  Camera camera_;
  Intersector& intersector_;
  RenderSettings settings_;
  std::vector<glm::vec3> geometric_normals_;        // per triangle, unit
  std::vector<ShadingTriangle> shading_triangles_;  // per triangle
  std::vector<Light> lights_;                       // the scene's, or the default light
  std::vector<SurfaceTerms> material_terms_;        // per material
  std::vector<PlainMaterial> plain_materials_;      // per material (plain_shading.h)
  SurfaceTextures surface_textures_;                // textures and vertex colours at hits
  SeeThroughHits see_through_;                      // rays past alphaMode MASK holes and BLEND
  // Ray cones (surface_textures.h): a camera ray's width at the camera, and the angle a
  // cone widens by per unit of distance (a pixel's; curvature ignored at bounces).
  float cone_origin_ = 0.0f, cone_spread_ = 0.0f;

  // Rays one chunk of a generation spawns while shading; concatenated in chunk order
  // afterwards, so the order is the rays' whatever thread shaded which chunk.
  // The vectors keep their sizes between frames; the counts say how much is in use.
  struct Spawned {
    std::vector<GrRay> shadow_rays;
    std::vector<ShadowRay> shadows;  // as many as shadow_rays
    size_t shadow_count = 0;
    std::vector<GrRay> rays;
    std::vector<PathRay> paths;  // as many as rays
    size_t ray_count = 0;
    std::vector<LightLanes> light_lanes;  // scratch: each light seen from a block of 16 hits
    std::vector<PlainLightLanes> plain_light_lanes;  // ... and its share of the plain hits
  };
  // One depth's arrays, kept from frame to frame, so each keeps about the size it had in
  // the last frame: growing a std::vector zero-fills its new part, which one set shared
  // by all depths did every frame (307k primary rays, then 25k, then 307k again).
  struct Generation {
    std::vector<GrRay> rays;  // the rays spawned for this depth (depth 0: primary_rays_)
    std::vector<PathRay> paths;
    std::vector<GrHit> hits;
    std::vector<glm::vec3> radiance;  // per ray: what it adds to its pixel, shadows apart
    // Headlight shading with one sample a pixel adds each ray's radiance to its pixel
    // itself (radiance stays unused): addPassRadiance has nothing left to add for it.
    bool radiance_in_pixels = false;
    size_t first_shadow = 0, shadow_count = 0;  // its shadow rays in shadow_rays_
  };
  std::vector<Generation> generations_;  // by depth, max_depth + 2 of them
  std::vector<GrRay> primary_rays_, batch_rays_;
  std::vector<GrHit> batch_hits_, light_hits_;
  // The pass's shadow rays, depth after depth (Generation::first_shadow), with the pixel
  // and light each belongs to, and their hits.
  std::vector<GrRay> shadow_rays_;
  std::vector<ShadowRay> shadows_;
  std::vector<GrHit> shadow_hits_;
  std::vector<float> shadow_light_share_;  // per shadow ray: the light past see-through surfaces
  // With several lights, each light's shadow rays in their order, and their indices in
  // shadow_rays_ (splitShadowsByLight).
  std::vector<std::vector<GrRay>> light_rays_;
  std::vector<std::vector<size_t>> light_ray_index_;
  std::vector<std::vector<size_t>> slice_light_counts_;  // scratch: per slice, rays per light
  std::vector<Spawned> spawned_;
  std::vector<size_t> chunk_offsets_;  // where each chunk's output starts (concatenateChunks)
  // The pixels the film holds (the crop window, or the whole image); the pixels traced,
  // radiance_ and the AOVs while rendering: the film's, and with adaptive AA one pixel
  // more on each side inside the image, since a pixel's refinement reads the centres of
  // its four neighbours (so a tile refines as the full render does); and, per rendered
  // pixel, its index in film_window_.
  const PixelWindow output_window_;
  const PixelWindow film_window_;
  std::vector<int> window_pixels_;
  // Each band's pixels (renderInBands), kept from frame to frame with the band and the
  // image width they were made for: a frame of three bands made them again every frame.
  struct BandPixels {
    PixelWindow band;
    int image_width = 0;
    std::vector<int> pixels;
  };
  std::vector<BandPixels> band_pixels_;
  std::vector<int> block_order_;  // the window's pixels in 4x4 blocks (pixel_blocks.h)
  int block_order_width_ = 0, block_order_height_ = 0;  // the window block_order_ is for
  PixelRadiance radiance_;                              // per film pixel accumulator
  SampleCoverage coverage_;  // per film pixel: camera samples and their hits (want_alpha)
};

}  // namespace gridrt
