#include "prepared_scene.h"

#include "adaptive_grid.h"
#include "aov_channels.h"
#include "brute_intersector.h"
#include "camera_rays.h"
#include "dda_intersector.h"
#include "device_step.h"
#include "prepared_triangles.h"
#include "reference_intersector.h"
#include "stopwatch.h"

namespace gridrt {

namespace {

std::unique_ptr<Intersector> makeIntersector(const Options& o, ClRuntime& runtime,
                                             const Scene& scene,
                                             const std::vector<GrTriangle>& triangles,
                                             const UniformGrid& grid, GridRtIntersector*& gridrt) {
  gridrt = nullptr;
  const KernelOptions kernel{o.watertight, o.pe_layout, o.transfer};
  if (o.accel == AccelKind::Brute)
    return std::make_unique<BruteIntersector>(runtime, triangles, kernel);
  if (o.accel == AccelKind::Reference) return std::make_unique<ReferenceIntersector>(scene);
  if (o.accel == AccelKind::Dda) return std::make_unique<DdaIntersector>(runtime, grid, kernel);
  auto g = std::make_unique<GridRtIntersector>(
      runtime, grid, o.pe_interrupt ? PeInterrupt::AllRays : PeInterrupt::CameraRays, kernel);
  gridrt = g.get();
  return g;
}

}  // namespace

RenderSettings renderSettings(const Options& o) {
  RenderSettings settings;
  settings.width = o.width;
  settings.height = o.height;
  settings.spp = o.spp;
  settings.max_depth = o.max_depth;
  settings.primary_only = o.primary_only;
  settings.background = o.background;
  settings.ambient = o.ambient;
  settings.ray_offset = o.ray_offset;
  settings.shading = o.shading;
  settings.adaptive_aa = o.adaptive_aa;
  settings.aa_samples = o.aa_samples;
  settings.aa_threshold = o.aa_threshold;
  settings.min_path_weight = o.min_path_weight;
  settings.max_pass_rays = size_t(o.wave_rays);
  if (o.crop) settings.crop = *o.crop;  // only the window's rays are traced
  // Filling them costs time per frame.
  settings.want_aovs = !o.aovs.empty() || !o.aov_layers.empty();
  settings.want_alpha = o.alpha;
  for (const auto& aov : o.aovs) settings.want_diagnostics |= isDiagnosticAov(aov.first);
  for (const auto& name : o.aov_layers) settings.want_diagnostics |= isDiagnosticAov(name);
  return settings;
}

PreparedScene::PreparedScene(const Options& o, ClRuntime& runtime, const Scene& scene,
                             const Camera& camera)
    : PreparedScene(o, runtime, scene, primaryRayOrigins(camera, o.width, o.height)) {}

PreparedScene::PreparedScene(const Options& o, ClRuntime& runtime, const Scene& scene,
                             const Bounds& ray_origins) {
  triangles_ = prepareTriangles(scene, KernelOptions{o.watertight});
  Stopwatch clock;
  uses_grid_ = o.accel == AccelKind::GridRt || o.accel == AccelKind::Dda;
  if (uses_grid_) {
    GridSettings settings = o.grid;
    settings.ray_origins = ray_origins;
    if (o.accel == AccelKind::Dda) settings.structure = GridStructure::Uniform;  // it walks voxels
    grid_ = buildGrid(triangles_, sceneBounds(scene), settings);
  }
  build_ms_ = clock.ms();
  clock.restart();
  intersector_ = during("building the kernels and uploading the scene", [&] {
    return makeIntersector(o, runtime, scene, triangles_, grid_, gridrt_);
  });
  setup_ms_ = clock.ms();
}

}  // namespace gridrt
