#include "application.h"

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <iostream>
#include <memory>
#include <optional>

#include "adaptive_grid.h"
#include "animated_scene.h"
#include "aov_channels.h"
#include "brute_intersector.h"
#include "camera_rays.h"
#include "choices_report.h"
#include "cl_runtime.h"
#include "crop_window.h"
#include "dda_intersector.h"
#include "default_scene.h"
#include "device_step.h"
#include "errors.h"
#include "frame_render.h"
#include "frame_sequence.h"
#include "frame_statistics.h"
#include "gltf_loader.h"
#include "gridrt_intersector.h"
#include "image_fits.h"
#include "image_output.h"
#include "mesh_import.h"
#include "missing_device.h"
#include "parallel_loops.h"
#include "prepared_scene.h"
#include "prepared_triangles.h"
#include "progress.h"
#include "reference_intersector.h"
#include "renderer.h"
#include "scene_source.h"
#include "standard_input_scene.h"
#include "standard_streams.h"
#include "stopwatch.h"
#include "texture_decoding.h"
#include "thread_count.h"
#include "uniform_grid.h"

namespace gridrt {

namespace {

// One frame a run renders: its number (--frames), the time it is posed at (--time,
// --frames; none: the still pose) and the files it writes.
struct FrameJob {
  long number = 0;
  std::optional<double> time;
  std::string output;
  std::vector<std::pair<std::string, std::string>> aovs;
  std::string aov_file;  // --aov-file, empty if none
};

std::vector<FrameJob> frameJobs(const Options& o) {
  if (!o.frames) return {FrameJob{0, o.time, o.output, o.aovs, o.aov_file}};
  const FramePattern output("-o", o.output);
  std::vector<FramePattern> aovs;
  for (const auto& aov : o.aovs) aovs.emplace_back("--aov " + aov.first, aov.second);
  std::vector<FrameJob> jobs;
  const std::optional<FramePattern> aov_file =
      o.aov_file.empty() ? std::nullopt
                         : std::optional<FramePattern>(FramePattern("--aov-file", o.aov_file));
  for (long f = o.frames->first; f <= o.frames->last; ++f) {
    FrameJob job{f, frameTime(f, o.fps), output.path(f), {}, aov_file ? aov_file->path(f) : ""};
    for (size_t a = 0; a < aovs.size(); ++a)
      job.aovs.emplace_back(o.aovs[a].first, aovs[a].path(f));
    jobs.push_back(std::move(job));
  }
  return jobs;
}

// --stats-json is written after the render: check its folder first, so that a typo does
// not cost a whole render (and leave an image without its statistics).
void validateStatsPath(const std::string& path) {
  if (path.empty() || path == kStandardOutput) return;
  std::filesystem::path p(path), dir = p.parent_path().empty() ? "." : p.parent_path();
  std::error_code ec;
  if (!std::filesystem::is_directory(dir, ec))
    throw RenderError("cannot write '" + path + "': directory '" + dir.string() +
                      "' does not exist");
  if (::access(dir.c_str(), W_OK) != 0)
    throw RenderError("cannot write '" + path + "': directory '" + dir.string() +
                      "' is not writable");
  if (std::filesystem::is_directory(p, ec))
    throw RenderError("cannot write '" + path + "': it is a directory");
}

// --aov-file's image: the film's R, G, B (and A) as the default layer, then each AOV of
// aov_layers as the layer "NAME." (aov_channels.h), every channel with its own miss value
// outside a crop window.
LayeredImage aovLayers(const Options& o, const Frame& frame) {
  LayeredImage layers = outputImage(o, frame);
  for (const std::string& name : o.aov_layers) {
    LayeredImage layer;
    layer.width = frame.film.width;
    layer.height = frame.film.height;
    layer.channels = aovChannels(frame.aovs, name, name + ".");
    layer = croppedImage(o, std::move(layer), aovMissValue(name));
    for (ImageChannel& c : layer.channels) layers.channels.push_back(std::move(c));
  }
  return layers;
}

void writeOutputs(const Options& o, const FrameJob& job, const Frame& frame) {
  writeLayeredImage(job.output, outputImage(o, frame), OutputKind::Image, o.format);
  if (!job.aov_file.empty())
    writeLayeredImage(job.aov_file, aovLayers(o, frame), OutputKind::Layers);
  for (const auto& aov : job.aovs) {
    LayeredImage image;
    image.width = frame.film.width;
    image.height = frame.film.height;
    image.channels = aovChannels(frame.aovs, aov.first, "");
    writeLayeredImage(aov.second, croppedImage(o, std::move(image), aovMissValue(aov.first)),
                      OutputKind::Aov);
  }
}

void printSummary(const Options& o, const Frame& frame, double median_frame,
                  const std::string& accel, const std::string& output) {
  uint64_t total_rays = frame.rays.total();
  std::string window;
  if (o.crop)
    window = " window " + std::to_string(o.crop->x0) + "," + std::to_string(o.crop->y0) + "-" +
             std::to_string(o.crop->x1) + "," + std::to_string(o.crop->y1) + ",";
  char line[512];
  std::snprintf(line, sizeof line,
                "gridrt: %dx%d,%s %llu rays (%llu primary, %llu shadow, %llu "
                "secondary), %.1f ms/frame, %.2f Mrays/s, %s -> %s\n",
                o.width, o.height, window.c_str(), (unsigned long long)total_rays,
                (unsigned long long)frame.rays.primary, (unsigned long long)frame.rays.shadow,
                (unsigned long long)(frame.rays.reflection + frame.rays.refraction), median_frame,
                median_frame > 0 ? total_rays / (median_frame * 1e3) : 0.0, accel.c_str(),
                output.c_str());
  std::cerr << line;
}

}  // namespace

int runApplication(const Options& given) {
  const ThreadLimit thread_limit(given.threads);
  if (given.list_devices) {
    auto devices = listDevices();
    if (devices.empty()) throw RenderError(missingDeviceMessage(1));
    std::cout << formatDeviceTable(devices);
    return 0;
  }
  // Fail on bad output paths and absurd sizes before spending time on anything.
  const std::vector<FrameJob> jobs = frameJobs(given);
  for (const FrameJob& job : jobs) {
    validateOutputPath(job.output, OutputKind::Image, given.format);
    // A name the program chose replaces nothing the user did not ask it to.
    if (!given.output_named && !given.force && std::filesystem::exists(job.output))
      throw UsageError("'" + job.output + "' exists: replace it with --force, or name the " +
                       "output with -o");
    for (const auto& aov : job.aovs) validateOutputPath(aov.second, OutputKind::Aov);
    if (!job.aov_file.empty()) validateOutputPath(job.aov_file, OutputKind::Layers);
  }
  validateStatsPath(given.stats_json);
  checkImageFitsHost(given);

  Stopwatch clock;
  Scene first_scene;
  const SceneSource source = loadScene(given, jobs.front().time, first_scene);
  double load_ms = clock.ms();
  if (!given.quiet) {
    for (const auto& w : given.warnings) std::cerr << "gridrt: warning: " << w << '\n';
    for (const auto& w : source.warnings) std::cerr << "gridrt: warning: " << w << '\n';
    for (const auto& w : first_scene.warnings) std::cerr << "gridrt: warning: " << w << '\n';
  }
  // A scene without a camera is framed on its still pose, whatever the frame.
  const Bounds framing =
      first_scene.has_camera
          ? Bounds{}
          : sceneBounds(source.animated ? source.animated->still() : first_scene);
  const Options o = sizedForCamera(given, chooseCamera(given, first_scene, framing));
  if (o.width != given.width) checkImageFitsHost(o);

  ClRuntime runtime(o.device);
  if (!o.quiet)
    std::cerr << "gridrt: device " << runtime.info().platform_index << ":"
              << runtime.info().device_index << " " << runtime.info().name << '\n';
  checkImageFitsDevice(o, runtime.info());

  const bool sequence = given.time || given.frames;
  ProgressBar bar(progressWanted(o.quiet), progressDelaySeconds());
  FramePhaseTimes all_phases;  // every timed frame of every frame job
  nlohmann::json stats, frames = nlohmann::json::array();
  double compile_ms = 0;
  uint64_t split_batches = 0;
  for (size_t i = 0; i < jobs.size(); ++i) {
    const FrameJob& job = jobs[i];
    clock.restart();
    Stopwatch job_clock;
    Scene posed;
    if (i > 0 && source.animated) {
      posed = source.animated->at(*job.time);
      posed.images = first_scene.images;  // decoded once, for the first frame
    }
    const Scene& scene = i > 0 && source.animated ? posed : first_scene;
    const double pose_ms = i > 0 ? clock.ms() : load_ms;
    const std::string note =
        jobs.size() > 1 ? "frame " + std::to_string(i + 1) + " of " + std::to_string(jobs.size())
                        : "";
    FrameResult result = renderScene(
        o, runtime, scene, chooseCamera(o, scene, framing),
        [&](double fraction) { bar.update((double(i) + fraction) / double(jobs.size()), note); },
        o.verbose && i == 0);
    writeOutputs(o, job, result.frame);
    all_phases.append(result.timings.phases);
    if (i == 0) compile_ms = result.setup_ms;
    split_batches += result.split_batches;
    if (sequence) {
      nlohmann::json entry = result.stats;
      entry["frame"] = job.number;
      entry["time"] = *job.time;
      entry["output"] = job.output;
      entry["pose_ms"] = pose_ms;
      entry["setup_ms"] = result.setup_ms;
      // The whole frame job: posing (the first's without loading), triangles, grid,
      // intersector, rendering and writing its files.
      entry["wall_ms"] = job_clock.ms();
      frames.push_back(std::move(entry));
    }
    if (i + 1 == jobs.size()) {
      bar.finish();
      stats = std::move(result.stats);
      // The top level: the medians over every timed frame of the run, the rest the last
      // frame's.
      stats.update(frameStatistics(all_phases, result.frame.rays));
      stats["frames_timed"] = all_phases.frame_ms.size();
      if (!o.quiet)
        printSummary(o, result.frame, median(all_phases.frame_ms), result.accel,
                     jobs.size() > 1
                         ? o.output + " (frames " + std::to_string(jobs.front().number) + ".." +
                               std::to_string(job.number) + ")"
                     : job.output == kStandardOutput ? "standard output"
                                                     : job.output);
    }
  }
  stats["device"] = runtime.info().name;
  stats["device_compute_units"] = runtime.info().compute_units;
  stats["device_type"] = runtime.info().type;
  stats["host_threads"] = parallelSliceCount();
  stats["scene"] = o.scene.empty()             ? "(default scene)"
                   : o.scene == kStandardInput ? "(standard input)"
                                               : o.scene;
  stats["load_ms"] = load_ms;
  stats["compile_ms"] = compile_ms;
  stats["programs"] = {{"loaded", runtime.programsLoaded()},
                       {"compiled", runtime.programsCompiled()}};
  if (sequence) {
    stats["animation_fps"] = o.fps;  // --fps (not a rendering speed)
    stats["frames"] = std::move(frames);
  }
  // Peak memory: the process's resident set (on a CPU device it holds the device buffers
  // too) and the device buffers' own peak.
  struct rusage usage {};
  getrusage(RUSAGE_SELF, &usage);
  stats["memory"] = {{"peak_host_mib", double(usage.ru_maxrss) / 1024.0},
                     {"peak_device_buffers_mib", double(runtime.peakBufferBytes()) / 1048576.0},
                     {"split_batches", split_batches}};
  if (!o.stats_json.empty()) writeJsonFile(o.stats_json, stats);
  // With -o - standard output carries the image alone.
  if (o.stats)
    (o.output == kStandardOutput ? std::cerr : std::cout) << formatStatisticsTable(stats);
  return 0;
}

}  // namespace gridrt
