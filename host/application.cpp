#include "application.h"

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>

#include "brute_intersector.h"
#include "camera_rays.h"
#include "cl_runtime.h"
#include "dda_intersector.h"
#include "default_scene.h"
#include "errors.h"
#include "frame_statistics.h"
#include "gltf_loader.h"
#include "gridrt_intersector.h"
#include "image_output.h"
#include "prepared_triangles.h"
#include "reference_intersector.h"
#include "renderer.h"
#include "stopwatch.h"
#include "uniform_grid.h"

namespace gridrt {

namespace {

// Host bytes one primary sample needs across the wavefront (rays, hits, paths, slots);
// used to refuse images that cannot fit before anything is allocated.
constexpr double kHostBytesPerSample = 400.0;

void checkImageFits(const Options& o, const DeviceInfo& device) {
  double samples = double(o.width) * o.height * o.spp;
  double need = samples * kHostBytesPerSample;
  double host = double(sysconf(_SC_PHYS_PAGES)) * double(sysconf(_SC_PAGE_SIZE));
  double limit = std::min(host, double(device.global_mem_bytes));
  if (need > limit)
    throw RenderError("image " + std::to_string(o.width) + "x" + std::to_string(o.height) +
                      " at " + std::to_string(o.spp) + " spp needs about " +
                      std::to_string(int(need / (1 << 20))) + " MiB, more than the " +
                      std::to_string(int(limit / (1 << 20))) + " MiB available");
}

Camera chooseCamera(const Options& o, const Scene& scene) {
  Camera camera = scene.has_camera ? scene.camera : defaultCamera(sceneBounds(scene));
  if (o.eye) {
    float yfov = camera.orthographic ? 0.6981317f : camera.yfov;
    camera = lookAtCamera(*o.eye, *o.target, yfov);
  }
  if (o.fov_degrees) {
    camera.orthographic = false;
    camera.yfov = *o.fov_degrees * 3.14159265f / 180.0f;
  }
  return camera;
}

std::vector<float> aovData(const PrimaryAovs& a, const std::string& name, int& channels) {
  channels = name == "normal" ? 3 : 1;
  if (name == "depth") return a.depth;
  if (name == "primid") return a.primid;
  if (name == "normal") return a.normal;
  if (name == "tests") return a.tests;
  if (name == "pe") return a.pe;
  return a.list_length;
}


}  // namespace

int runApplication(const Options& o) {
  if (o.list_devices) {
    auto devices = listDevices();
    if (devices.empty())
      throw RenderError("no OpenCL platform found: install an OpenCL driver, e.g. 'apt-get "
                        "install pocl-opencl-icd'");
    std::cout << formatDeviceTable(devices);
    return 0;
  }
  // Fail on bad output paths before spending time on the render.
  validateOutputPath(o.output);
  for (const auto& aov : o.aovs) validateOutputPath(aov.second, OutputKind::Aov);

  Stopwatch clock;
  Scene scene = o.scene.empty() ? makeDefaultScene() : loadGltfFile(o.scene, GltfLoadOptions{o.camera_name});
  double load_ms = clock.ms();
  if (!o.quiet)
    for (const auto& w : scene.warnings) std::cerr << "gridrt: warning: " << w << '\n';
  Camera camera = chooseCamera(o, scene);

  ClRuntime runtime(o.device);
  if (!o.quiet)
    std::cerr << "gridrt: device " << runtime.info().platform_index << ":"
              << runtime.info().device_index << " " << runtime.info().name << '\n';
  checkImageFits(o, runtime.info());

  std::vector<GrTriangle> triangles = prepareTriangles(scene);
  clock.restart();
  UniformGrid grid;
  bool uses_grid = o.accel == AccelKind::GridRt || o.accel == AccelKind::Dda;
  if (uses_grid) grid = buildUniformGrid(triangles, sceneBounds(scene), o.grid);
  double build_ms = clock.ms();

  clock.restart();
  std::unique_ptr<Intersector> intersector;
  GridRtIntersector* gridrt = nullptr;
  if (o.accel == AccelKind::Brute) {
    intersector = std::make_unique<BruteIntersector>(runtime, triangles);
  } else if (o.accel == AccelKind::Reference) {
    intersector = std::make_unique<ReferenceIntersector>(scene);
  } else if (o.accel == AccelKind::Dda) {
    intersector = std::make_unique<DdaIntersector>(runtime, grid);
  } else {
    auto g = std::make_unique<GridRtIntersector>(runtime, grid, o.pe_interrupt);
    gridrt = g.get();
    intersector = std::move(g);
  }
  double compile_ms = clock.ms();

  RenderSettings settings;
  settings.width = o.width;
  settings.height = o.height;
  settings.spp = o.spp;
  settings.max_depth = o.max_depth;
  settings.primary_only = o.primary_only;
  settings.background = o.background;
  settings.ambient = o.ambient;
  settings.ray_offset = o.ray_offset;
  for (const auto& aov : o.aovs)
    settings.want_diagnostics |= aov.first == "tests" || aov.first == "pe" || aov.first == "listlen";
  Renderer renderer(scene, camera, *intersector, settings);

  // The first frame warms up (buffers, caches); with --repeat, medians come from the rest.
  Frame frame;
  std::vector<double> frame_ms, kernel_ms, shade_ms, lists_ms, reduce_ms, intersect_ms;
  IntersectCounters first_frame_counters;
  for (int f = 0; f <= o.repeat; ++f) {
    IntersectCounters before = intersector->counters();
    renderer.render(frame);
    const IntersectCounters& after = intersector->counters();
    if (f == 0) {
      first_frame_counters = after;
      if (o.repeat > 0) continue;
    }
    frame_ms.push_back(frame.times.frame_ms);
    shade_ms.push_back(frame.times.shade_ms);
    intersect_ms.push_back(frame.times.intersect_ms);
    kernel_ms.push_back(after.kernel_ms - before.kernel_ms);
    lists_ms.push_back(after.lists_ms - before.lists_ms);
    reduce_ms.push_back(after.reduce_ms - before.reduce_ms);
  }

  writeImage(o.output, frame.film);
  for (const auto& aov : o.aovs) {
    int channels = 1;
    std::vector<float> data = aovData(frame.aovs, aov.first, channels);
    writeAov(aov.second, o.width, o.height, channels, data);
  }

  double median_frame = median(frame_ms);
  uint64_t total_rays = frame.rays.total();
  nlohmann::json stats;
  stats["device"] = runtime.info().name;
  stats["scene"] = o.scene.empty() ? "(default scene)" : o.scene;
  stats["triangles"] = scene.triangleCount();
  stats["width"] = o.width;
  stats["height"] = o.height;
  stats["spp"] = o.spp;
  stats["max_depth"] = o.max_depth;
  stats["accel"] = intersector->name();
  stats["frames_timed"] = frame_ms.size();
  stats["rays"] = {{"primary", frame.rays.primary},       {"shadow", frame.rays.shadow},
                   {"reflection", frame.rays.reflection}, {"refraction", frame.rays.refraction},
                   {"total", total_rays}};
  stats["load_ms"] = load_ms;
  stats["build_ms"] = build_ms;
  stats["compile_ms"] = compile_ms;
  stats["lists_ms"] = median(lists_ms);
  stats["kernel_ms"] = median(kernel_ms);
  stats["reduce_ms"] = median(reduce_ms);
  stats["intersect_ms"] = median(intersect_ms);
  stats["shade_ms"] = median(shade_ms);
  stats["frame_ms"] = median_frame;
  stats["mrays_per_s"] = median_frame > 0 ? total_rays / (median_frame * 1e3) : 0.0;
  const IntersectCounters& c = first_frame_counters;
  stats["tests_per_ray"] = c.rays ? double(c.tests) / double(c.rays) : 0.0;
  if (uses_grid) {
    std::vector<int> refs(grid.peCount());
    for (int pe = 0; pe < grid.peCount(); ++pe) refs[pe] = grid.triangleCountOfPe(pe);
    MeanMax r = meanMax(refs);
    stats["grid"] = {{"dims", {grid.info.nx, grid.info.ny, grid.info.nz}},
                     {"voxels", grid.voxelCount()},
                     {"pes", grid.peCount()},
                     {"refs_per_pe_mean", r.mean},
                     {"refs_per_pe_max", r.max},
                     {"memory_bytes", grid.memoryBytes()},
                     {"build_ms", build_ms},
                     {"margin", grid.margin}};
  }
  if (gridrt) {
    MeanMax rays_pe = meanMax(gridrt->raysPerPe()), tests_pe = meanMax(gridrt->testsPerPe());
    double frames = double(o.repeat + 1);
    stats["lists"] = {{"length_mean", c.rays ? double(c.list_entries) / double(c.rays) : 0.0},
                      {"length_max", gridrt->maxListLength()},
                      {"list_ms", median(lists_ms)}};
    stats["pe_load"] = {{"rays_mean", rays_pe.mean / frames}, {"rays_max", rays_pe.max / frames},
                        {"tests_mean", tests_pe.mean / frames},
                        {"tests_max", tests_pe.max / frames}};
    stats["interrupt"] = {{"enabled", o.pe_interrupt}, {"skipped_pairs", c.skipped_pairs}};
  }
  if (!o.stats_json.empty()) writeJsonFile(o.stats_json, stats);
  if (o.stats) std::cout << formatStatisticsTable(stats);
  if (!o.quiet) {
    char line[256];
    std::snprintf(line, sizeof line, "gridrt: %dx%d, %llu rays (%llu primary, %llu shadow, %llu "
                  "secondary), %.1f ms/frame, %.2f Mrays/s, %s -> %s\n",
                  o.width, o.height, (unsigned long long)total_rays,
                  (unsigned long long)frame.rays.primary, (unsigned long long)frame.rays.shadow,
                  (unsigned long long)(frame.rays.reflection + frame.rays.refraction),
                  median_frame, median_frame > 0 ? total_rays / (median_frame * 1e3) : 0.0,
                  intersector->name().c_str(), o.output.c_str());
    std::cerr << line;
  }
  return 0;
}

}  // namespace gridrt
