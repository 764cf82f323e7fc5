// The CPU peer GridRT is measured against: Embree 3 (Debian's libembree-dev,
// tools/embree_intersector.h) on the same scene, on the same machine, in the same run of
// tools/bench.py. Built only where CMake finds Embree (tools/setup.sh --bench).
//
//   embree_peer SCENE.glb --width W --height H [--threads T] [--packet 1|8|16]
//               [--frames N] [--primid OUT.exr] [--depth OUT.exr]
//   embree_peer [SCENE.glb] --whitted [--width W --height H --max-depth D -o OUT.png ...]
//   embree_peer SCENE.glb --whitted --sequence A:B [--fps F] [--width W --height H ...]
//
// Camera rays (the default): gridrt's centre rays (CameraRayGenerator, the scene's camera
// or the default one), made once; a frame is tracing them all (closest hit) on T host
// threads, one ray at a time (rtcIntersect1) or in coherent packets of 4x2 / 4x4 pixels
// (rtcIntersect8 / 16). Ray generation and shading are not in the frame, so the figure
// flatters Embree against gridrt's frame, which has both. --primid writes each pixel's
// triangle (the scene's global index, -1 on a miss) and --depth its hit distance (-1 on a
// miss), the formats of gridrt --aov primid / depth.
// --whitted: gridrt's own Whitted renderer (host/render/renderer.h, its default settings) with
// Embree as its intersector, on the scene or without one on gridrt's built-in default
// scene: the same frame as `gridrt` renders, ray generation, shading and shadow rays
// included, only the tracing Embree's. -o writes the image. With --primary-only, the frame
// gridrt --primary-only renders (camera rays, headlight shading), Embree tracing.
// --sequence: an animated scene's frames A..B at frame / F seconds (docs/animation.md), each
// posed, its BVH built anew and one Whitted frame rendered, as gridrt --frames does with
// its grid; the JSON line lists each frame's pose_ms, build_ms and frame_ms.
// The BVH is Embree's high-quality build. Prints one line of JSON: build_ms, the median
// frame_ms of --frames frames after a warm-up, mrays_per_s, hits or (--whitted) fps and
// the frame's phases.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <string>
#include <vector>

#include "animated_scene.h"
#include "camera_rays.h"
#include "default_scene.h"
#include "embree_intersector.h"
#include "errors.h"
#include "frame_sequence.h"
#include "frame_statistics.h"
#include "gltf_loader.h"
#include "image_output.h"
#include "parallel_loops.h"
#include "pinhole_view.h"
#include "prepared_triangles.h"
#include "renderer.h"
#include "stopwatch.h"

namespace {

using namespace gridrt;

struct PeerOptions {
  std::string scene, primid_path, depth_path, output, sequence;
  double fps = 24.0;
  int width = 320, height = 240, threads = 2, packet = 1, frames = 7, max_depth = 5;
  bool whitted = false, primary_only = false;
};

// The options through CLI11, as gridrt parses its own; a bad one is one line on stderr
// and exit code 2, --help prints the usage and exits 0.
PeerOptions parse(int argc, char** argv) {
  PeerOptions o;
  CLI::App app{"Embree 3 on gridrt's camera rays or in its Whitted renderer (tools/bench.py)",
               "embree_peer"};
  app.add_option("scene", o.scene,
                 "glTF 2.0 scene (.gltf or .glb; --whitted: default scene without)");
  app.add_option("--width", o.width, "image width")->check(CLI::Range(1, 65536));
  app.add_option("--height", o.height, "image height")->check(CLI::Range(1, 65536));
  app.add_option("--threads", o.threads, "host and Embree threads")->check(CLI::Range(1, 1024));
  app.add_option("--packet", o.packet, "rays per rtcIntersect call")
      ->check(CLI::IsMember({1, 8, 16}));
  app.add_option("--frames", o.frames, "timed frames after a warm-up")
      ->check(CLI::Range(1, 100000));
  app.add_option("--primid", o.primid_path, "write each pixel's triangle (.exr)");
  app.add_option("--depth", o.depth_path, "write each pixel's hit distance (.exr)");
  app.add_flag("--whitted", o.whitted, "whole Whitted frames through gridrt's renderer");
  app.add_option("--max-depth", o.max_depth, "--whitted: reflection/refraction bounces")
      ->check(CLI::Range(0, 64));
  app.add_option("-o,--output", o.output, "--whitted: write the image (.png/.jpg/.exr)");
  app.add_option("--sequence", o.sequence,
                 "--whitted: A:B an animated scene's frames, each posed, built and rendered");
  app.add_option("--fps", o.fps, "--sequence: frames per second")->check(CLI::Range(0.001, 1e6));
  app.add_flag("--primary-only", o.primary_only,
               "--whitted: primary rays only, headlight shading (as gridrt --primary-only)");
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp&) {
    std::cout << app.help();
    std::exit(0);
  } catch (const CLI::ParseError& e) {
    std::string what = e.what();
    std::replace(what.begin(), what.end(), '\n', ' ');
    std::cerr << "embree_peer: " << what << " (see embree_peer --help)\n";
    std::exit(2);
  }
  const bool camera_only = !o.primid_path.empty() || !o.depth_path.empty();
  const char* problem = !o.whitted && o.scene.empty() ? "a scene is needed without --whitted"
                        : o.whitted && camera_only
                            ? "--primid and --depth are for camera rays, not --whitted"
                        : !o.whitted && !o.output.empty() ? "-o is for --whitted"
                        : !o.sequence.empty() && (!o.whitted || o.scene.empty())
                            ? "--sequence needs --whitted and a scene"
                            : nullptr;
  if (problem) {
    std::cerr << "embree_peer: " << problem << " (see embree_peer --help)\n";
    std::exit(2);
  }
  return o;
}

Scene loadPeerScene(const PeerOptions& o) {
  Scene scene = o.scene.empty() ? makeDefaultScene() : loadGltfFile(o.scene);
  if (scene.triangleCount() == 0) throw SceneError("'" + o.scene + "' has no triangles");
  return scene;
}

// Camera rays: made once, then traced every frame.
int runCameraRays(const PeerOptions& o, const Scene& scene, const Camera& camera,
                  EmbreeIntersector& embree) {
  CameraRayGenerator generator(camera, o.width, o.height);
  const PixelWindow image{0, 0, o.width, o.height};
  std::vector<GrRay> rays(size_t(o.width) * o.height);
  generator.centreWindow(image, rays.data());
  const PinholeView view = PinholeView::of(camera, o.width, o.height, image);

  std::vector<GrHit> hits;
  std::vector<double> frame_ms;
  Stopwatch clock;
  for (int f = 0; f <= o.frames; ++f) {  // frame 0 warms up
    clock.restart();
    if (camera.orthographic)
      embree.intersect(rays, HitMode::Closest, hits, nullptr);
    else
      embree.intersectPrimary(view, rays, hits, nullptr);
    if (f > 0) frame_ms.push_back(clock.ms());
  }
  const double frame_median = median(frame_ms);
  const long long count =
      std::count_if(hits.begin(), hits.end(), [](const GrHit& h) { return h.prim >= 0; });
  if (!o.primid_path.empty()) {
    std::vector<float> ids(hits.size());
    for (size_t p = 0; p < hits.size(); ++p) ids[p] = float(hits[p].prim);
    writeAov(o.primid_path, o.width, o.height, 1, ids);
  }
  if (!o.depth_path.empty()) {
    std::vector<float> depth(hits.size());
    for (size_t p = 0; p < hits.size(); ++p) depth[p] = hits[p].prim >= 0 ? hits[p].t : -1.0f;
    writeAov(o.depth_path, o.width, o.height, 1, depth);
  }
  const nlohmann::json stats = {{"build_ms", embree.buildMs()},
                                {"frame_ms", frame_median},
                                {"mrays_per_s", rays.size() / (frame_median * 1e3)},
                                {"rays", rays.size()},
                                {"hits", count},
                                {"threads", o.threads},
                                {"packet", o.packet},
                                {"triangles", scene.triangleCount()}};
  std::printf("%s\n", stats.dump().c_str());
  return 0;
}

// Whole Whitted frames: gridrt's renderer with its default settings, Embree tracing.
int runWhitted(const PeerOptions& o, const Scene& scene, const Camera& camera,
               EmbreeIntersector& embree) {
  RenderSettings settings;
  settings.width = o.width;
  settings.height = o.height;
  settings.max_depth = o.max_depth;
  settings.primary_only = o.primary_only;
  settings.want_aovs = false;
  Renderer renderer(scene, camera, embree, settings);
  Frame frame;
  FramePhaseTimes phases;
  for (int f = 0; f <= o.frames; ++f) {  // frame 0 warms up
    renderer.render(frame);
    if (f > 0) phases.add(frame.times);
  }
  if (!o.output.empty()) writeImage(o.output, frame.film);
  // gridrt's frame figures (frame_statistics.h), and the peer's own.
  nlohmann::json stats = frameStatistics(phases, frame.rays);
  stats["fps"] = 1e3 / stats["frame_ms"].get<double>();
  stats["build_ms"] = embree.buildMs();
  stats["rays"] = frame.rays.total();
  stats["threads"] = o.threads;
  stats["packet"] = o.packet;
  stats["triangles"] = scene.triangleCount();
  std::printf("%s\n", stats.dump().c_str());
  return 0;
}

// An animated scene's frames: each posed, its BVH built and one Whitted frame rendered.
int runSequence(const PeerOptions& o) {
  const FrameRange range = parseFrameRange(o.sequence);
  const AnimatedScene animated(GltfDocument::fromFile(o.scene), {}, "");
  const Scene still = animated.still();
  const tbb::global_control host_threads(tbb::global_control::max_allowed_parallelism,
                                         size_t(std::max(1, o.threads)));
  RenderSettings settings;
  settings.width = o.width;
  settings.height = o.height;
  settings.max_depth = o.max_depth;
  settings.primary_only = o.primary_only;
  settings.want_aovs = false;
  nlohmann::json frames = nlohmann::json::array();
  for (long k = range.first; k <= range.last; ++k) {
    Stopwatch clock;
    const Scene scene = animated.at(frameTime(k, o.fps));
    const double pose_ms = clock.ms();
    const Camera camera = scene.has_camera ? scene.camera : defaultCamera(sceneBounds(still));
    EmbreeIntersector embree(scene, o.threads, o.packet);
    Renderer renderer(scene, camera, embree, settings);
    Frame frame;
    renderer.render(frame);
    frames.push_back({{"frame", k},
                      {"pose_ms", pose_ms},
                      {"build_ms", embree.buildMs()},
                      {"frame_ms", frame.times.frame_ms},
                      {"wall_ms", clock.ms()},
                      {"rays", frame.rays.total()},
                      {"triangles", scene.triangleCount()}});
  }
  const nlohmann::json stats = {{"frames", frames}, {"threads", o.threads}, {"packet", o.packet}};
  std::printf("%s\n", stats.dump().c_str());
  return 0;
}

int run(const PeerOptions& o) {
  if (!o.sequence.empty()) return runSequence(o);
  if (o.whitted && !o.output.empty()) validateOutputPath(o.output);
  const Scene scene = loadPeerScene(o);
  const Camera camera = scene.has_camera ? scene.camera : defaultCamera(sceneBounds(scene));
  const tbb::global_control host_threads(tbb::global_control::max_allowed_parallelism,
                                         size_t(std::max(1, o.threads)));
  EmbreeIntersector embree(scene, o.threads, o.packet);
  return o.whitted ? runWhitted(o, scene, camera, embree) : runCameraRays(o, scene, camera, embree);
}

}  // namespace

int main(int argc, char** argv) {
  const PeerOptions options = parse(argc, argv);
  try {
    return run(options);
  } catch (const std::exception& e) {
    std::cerr << "embree_peer: " << e.what() << '\n';
    return 1;
  }
}
