#include "frame_render.h"

#include <algorithm>
#include <iostream>

#include "choices_report.h"
#include "crop_window.h"
#include "device_step.h"
#include "gridrt_intersector.h"
#include "image_output.h"
#include "prepared_scene.h"
#include "uniform_grid.h"

namespace gridrt {

namespace {

// Renders 1 + --repeat frames into `frame`. The first frame warms up (buffers, caches);
// with --repeat, medians come from the rest. progress(fraction) is told how far all of
// them are.
FrameTimings renderFrames(const Options& o, Renderer& renderer, Intersector& intersector,
                          Frame& frame, const std::function<void(double)>& progress) {
  FrameTimings t;
  const int frames = o.repeat + 1;
  for (int f = 0; f < frames; ++f) {
    IntersectCounters before = intersector.counters();
    renderer.render(frame, [&](int done, int total) {
      progress((f + double(done) / std::max(total, 1)) / frames);
    });
    const IntersectCounters& after = intersector.counters();
    if (f == 0) {
      t.first_frame_counters = after;
      if (o.repeat > 0) continue;
    }
    t.phases.add(frame.times);
    t.kernel_ms.push_back(after.kernel_ms - before.kernel_ms);
    t.device_ms.push_back(after.device_ms - before.device_ms);
    t.transfer_ms.push_back(after.transfer_ms - before.transfer_ms);
    t.lists_ms.push_back(after.listsMs() - before.listsMs());
    t.walk_ms.push_back(after.walk_ms - before.walk_ms);
    t.binning_ms.push_back(after.binning_ms - before.binning_ms);
    t.bundling_ms.push_back(after.bundling_ms - before.bundling_ms);
    t.reduce_ms.push_back(after.reduce_ms - before.reduce_ms);
  }
  return t;
}

}  // namespace

// Prepares the scene's triangles, builds its grid and intersector (the runtime keeps the
// programs it built, so only the first frame of a run compiles or loads them) and renders
// 1 + --repeat frames. With report_choices, prints what was chosen first (-v).
FrameResult renderScene(const Options& o, ClRuntime& runtime, const Scene& scene,
                        const Camera& camera, const std::function<void(double)>& progress,
                        bool report_choices) {
  FrameResult result;
  PreparedScene prepared(o, runtime, scene, camera);
  const UniformGrid* grid = prepared.grid();
  const bool uses_grid = grid != nullptr;
  const double build_ms = prepared.buildMs();
  if (report_choices)
    for (const std::string& line : choicesReport(o, scene, camera, grid, build_ms))
      std::cerr << "gridrt: " << line << '\n';
  Intersector* intersector = &prepared.intersector();
  GridRtIntersector* gridrt = prepared.gridrt();
  result.setup_ms = prepared.setupMs();
  result.accel = intersector->name();

  Renderer renderer(scene, camera, *intersector, renderSettings(o));
  Frame& frame = result.frame;
  result.timings =
      during("rendering", [&] { return renderFrames(o, renderer, *intersector, frame, progress); });
  const FrameTimings& t = result.timings;

  uint64_t total_rays = frame.rays.total();
  nlohmann::json stats = frameStatistics(t.phases, frame.rays);
  stats["triangles"] = scene.triangleCount();
  stats["width"] = o.width;
  stats["height"] = o.height;
  stats["spp"] = o.spp;
  stats["max_depth"] = o.max_depth;
  stats["accel"] = intersector->name();
  stats["intersector"] = o.accel == AccelKind::Reference ? "double"
                         : o.watertight                  ? "watertight"
                                                         : "mt";
  stats["aa"] = o.adaptive_aa ? "adaptive" : "uniform";
  stats["refined_pixels"] = frame.refined_pixels;
  stats["passes"] = frame.passes;
  stats["frames_timed"] = t.phases.frame_ms.size();
  stats["rays"] = {{"primary", frame.rays.primary},         {"shadow", frame.rays.shadow},
                   {"reflection", frame.rays.reflection},   {"refraction", frame.rays.refraction},
                   {"see_through", frame.rays.see_through}, {"total", total_rays}};
  stats["build_ms"] = build_ms;
  stats["lists_ms"] = median(t.lists_ms);
  stats["kernel_ms"] = median(t.kernel_ms);
  stats["kernel_device_ms"] = median(t.device_ms);
  stats["transfer_device_ms"] = median(t.transfer_ms);
  stats["reduce_ms"] = median(t.reduce_ms);
  stats["generate_ms"] = frame.times.generate_ms;  // primary rays of the last frame
  const IntersectCounters& c = t.first_frame_counters;
  stats["tests_per_ray"] = c.rays ? double(c.tests) / double(c.rays) : 0.0;
  stats["tests_run_per_ray"] = c.rays ? double(c.tests_run) / double(c.rays) : 0.0;
  // A frame's 16-lane PE packets and the kernels' device time over them: their fixed cost.
  stats["kernel_packets"] = c.packets;
  stats["kernel_ns_per_packet"] = c.packets ? median(t.device_ms) * 1e6 / double(c.packets) : 0.0;
  if (uses_grid) {
    std::vector<int> refs(grid->peCount());
    for (int pe = 0; pe < grid->peCount(); ++pe) refs[pe] = grid->triangleCountOfPe(pe);
    MeanMax r = meanMax(refs);
    stats["grid"] = {{"structure", grid->adaptive.empty() ? "uniform" : "adaptive"},
                     {"depth", grid->adaptive.depth},
                     {"dims", {grid->info.nx, grid->info.ny, grid->info.nz}},
                     {"voxels", grid->voxelCount()},
                     {"pes", grid->peCount()},
                     {"refs_per_pe_mean", r.mean},
                     {"refs_per_pe_max", r.max},
                     {"memory_bytes", grid->memoryBytes()},
                     {"build_ms", build_ms},
                     {"margin", grid->margin}};
  }
  if (gridrt) {
    MeanMax rays_pe = meanMax(gridrt->raysPerPe()), tests_pe = meanMax(gridrt->testsPerPe());
    double frames = double(o.repeat + 1);
    stats["lists"] = {
        {"length_mean", c.rays ? double(c.list_entries) / double(c.rays) : 0.0},
        {"length_max", gridrt->maxListLengthKnown() ? nlohmann::json(gridrt->maxListLength())
                                                    : nlohmann::json(nullptr)},
        {"list_ms", median(t.lists_ms)},
        {"walk_ms", median(t.walk_ms)},
        {"binning_ms", median(t.binning_ms)},
        {"bundling_ms", median(t.bundling_ms)}};
    stats["pe_load"] = {{"rays_mean", rays_pe.mean / frames},
                        {"rays_max", rays_pe.max / frames},
                        {"tests_mean", tests_pe.mean / frames},
                        {"tests_max", tests_pe.max / frames}};
    stats["pe_layout"] = gridrt->peLayout() == PeLayout::Lanes ? "lanes" : "packets";
    stats["transfer"] = gridrt->batchTransfer() == BatchTransfer::Copy ? "copy" : "map";
    stats["interrupt"] = {{"camera_rays", gridrt->cameraInterrupt()},
                          {"all_rays", gridrt->allInterrupt()},
                          {"skipped_pairs", c.skipped_pairs}};
  }
  result.split_batches = c.split_batches;
  result.stats = std::move(stats);
  return result;
}

LayeredImage croppedImage(const Options& o, LayeredImage image, float outside) {
  if (!o.crop) return image;
  if (o.crop_output == CropOutput::Window) {
    image.x = o.crop->x0;
    image.y = o.crop->y0;
    image.full_width = o.width;
    image.full_height = o.height;
    return image;
  }
  for (ImageChannel& c : image.channels)
    if (c.type == SampleType::Float)
      c.floats = placeWindow(c.floats, o.width, o.height, 1, *o.crop, outside);
    else
      c.uints = placeWindow(c.uints, o.width, o.height, 1, *o.crop, uint32_t(int32_t(outside)));
  image.width = o.width;
  image.height = o.height;
  return image;
}

LayeredImage outputImage(const Options& o, const Frame& frame) {
  return croppedImage(o, filmImage(frame.film), 0.0f);
}

}  // namespace gridrt
