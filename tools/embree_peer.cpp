// The CPU peer the speed issue measures GridRT against: Embree 3 (Debian's libembree-dev)
// tracing the same primary rays of the same scene, on the same machine, in the same run
// of tools/bench.py. Built only where CMake finds Embree (tools/setup.sh --bench).
//
//   embree_peer SCENE.glb --width W --height H [--threads T] [--packet 1|8|16]
//               [--frames N] [--primid OUT.exr] [--depth OUT.exr]
//
// The rays are gridrt's centre rays (CameraRayGenerator, the scene's camera or the default
// one), made once; a frame is tracing them all (closest hit), rows spread over T OpenMP
// threads, one ray at a time (rtcIntersect1) or in coherent packets of 4x2 / 4x4 pixels
// (rtcIntersect8 / 16). Ray generation and shading are not in the frame, so the figure
// flatters Embree against gridrt's frame, which has both. The BVH is Embree's
// high-quality build. Prints one line of JSON: build_ms, the median frame_ms of --frames
// frames after a warm-up, mrays_per_s, hits. --primid writes each pixel's triangle
// (the scene's global index, -1 on a miss) and --depth its hit distance (-1 on a miss),
// the formats of gridrt --aov primid / depth.
#include <embree3/rtcore.h>
#include <omp.h>

#include <CLI/CLI.hpp>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <limits>
#include <string>
#include <vector>

#include "camera_rays.h"
#include "errors.h"
#include "frame_statistics.h"
#include "gltf_loader.h"
#include "image_output.h"
#include "prepared_triangles.h"
#include "stopwatch.h"

namespace {

using namespace gridrt;

struct PeerOptions {
  std::string scene, primid_path, depth_path;
  int width = 320, height = 240, threads = 2, packet = 1, frames = 7;
};

// The options through CLI11, as gridrt parses its own; a bad one is one line on stderr
// and exit code 2, --help prints the usage and exits 0.
PeerOptions parse(int argc, char** argv) {
  PeerOptions o;
  CLI::App app{"Embree 3 on gridrt's camera rays (tools/bench.py)", "embree_peer"};
  app.add_option("scene", o.scene, "glTF 2.0 scene (.gltf or .glb)")->required();
  app.add_option("--width", o.width, "image width")->check(CLI::Range(1, 65536));
  app.add_option("--height", o.height, "image height")->check(CLI::Range(1, 65536));
  app.add_option("--threads", o.threads, "OpenMP and Embree threads")->check(CLI::Range(1, 1024));
  app.add_option("--packet", o.packet, "rays per rtcIntersect call")
      ->check(CLI::IsMember({1, 8, 16}));
  app.add_option("--frames", o.frames, "timed frames after a warm-up")
      ->check(CLI::Range(1, 100000));
  app.add_option("--primid", o.primid_path, "write each pixel's triangle (.exr)");
  app.add_option("--depth", o.depth_path, "write each pixel's hit distance (.exr)");
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
  return o;
}

// The scene's triangles as one Embree geometry, primID = the global triangle index.
RTCScene buildScene(RTCDevice device, const Scene& scene) {
  RTCScene rtc_scene = rtcNewScene(device);
  rtcSetSceneBuildQuality(rtc_scene, RTC_BUILD_QUALITY_HIGH);
  RTCGeometry geometry = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
  rtcSetGeometryBuildQuality(geometry, RTC_BUILD_QUALITY_HIGH);
  const size_t triangles = scene.triangleCount();
  auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(
      geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), 3 * triangles));
  auto* indices = static_cast<unsigned*>(rtcSetNewGeometryBuffer(
      geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), triangles));
  for (size_t v = 0; v < 3 * triangles; ++v) {
    vertices[3 * v] = scene.positions[v].x;
    vertices[3 * v + 1] = scene.positions[v].y;
    vertices[3 * v + 2] = scene.positions[v].z;
    indices[v] = unsigned(v);
  }
  rtcCommitGeometry(geometry);
  rtcAttachGeometry(rtc_scene, geometry);
  rtcReleaseGeometry(geometry);
  rtcCommitScene(rtc_scene);
  return rtc_scene;
}

// One frame, one ray at a time: each pixel's triangle into prim.
void traceSingle(RTCScene scene, const std::vector<GrRay>& rays, std::vector<int>& prim,
                 std::vector<float>& depth) {
#pragma omp parallel for schedule(dynamic, 1024)
  for (long long p = 0; p < (long long)rays.size(); ++p) {
    const GrRay& r = rays[p];
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRayHit rh;
    rh.ray.org_x = r.ox; rh.ray.org_y = r.oy; rh.ray.org_z = r.oz; rh.ray.tnear = r.tmin;
    rh.ray.dir_x = r.dx; rh.ray.dir_y = r.dy; rh.ray.dir_z = r.dz; rh.ray.time = 0.0f;
    rh.ray.tfar = r.tmax; rh.ray.mask = ~0u; rh.ray.id = 0; rh.ray.flags = 0;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(scene, &context, &rh);
    const bool hit = rh.hit.geomID != RTC_INVALID_GEOMETRY_ID;
    prim[p] = hit ? int(rh.hit.primID) : -1;
    depth[p] = hit ? rh.ray.tfar : -1.0f;
  }
}

// The packet types and calls of one width: tiles of 4 x (N / 4) pixels.
template <int N> struct Packet;
template <> struct Packet<8> {
  using RayHit = RTCRayHit8;
  static void intersect(const int* valid, RTCScene s, RTCIntersectContext* c, RayHit* rh) {
    rtcIntersect8(valid, s, c, rh);
  }
};
template <> struct Packet<16> {
  using RayHit = RTCRayHit16;
  static void intersect(const int* valid, RTCScene s, RTCIntersectContext* c, RayHit* rh) {
    rtcIntersect16(valid, s, c, rh);
  }
};

template <int N>
void tracePackets(RTCScene scene, const std::vector<GrRay>& rays, int width, int height,
                  std::vector<int>& prim, std::vector<float>& depth) {
  constexpr int kTileW = 4, kTileH = N / 4;
  const int tiles_x = (width + kTileW - 1) / kTileW, tiles_y = (height + kTileH - 1) / kTileH;
#pragma omp parallel for schedule(dynamic, 16)
  for (long long tile = 0; tile < (long long)tiles_x * tiles_y; ++tile) {
    const int x0 = int(tile % tiles_x) * kTileW, y0 = int(tile / tiles_x) * kTileH;
    alignas(64) int valid[N];
    alignas(64) typename Packet<N>::RayHit rh;
    long long pixel[N];
    for (int k = 0; k < N; ++k) {
      const int x = x0 + k % kTileW, y = y0 + k / kTileW;
      valid[k] = x < width && y < height ? -1 : 0;
      pixel[k] = valid[k] ? (long long)y * width + x : 0;
      const GrRay& r = rays[pixel[k]];
      rh.ray.org_x[k] = r.ox; rh.ray.org_y[k] = r.oy; rh.ray.org_z[k] = r.oz;
      rh.ray.dir_x[k] = r.dx; rh.ray.dir_y[k] = r.dy; rh.ray.dir_z[k] = r.dz;
      rh.ray.tnear[k] = r.tmin; rh.ray.tfar[k] = r.tmax; rh.ray.time[k] = 0.0f;
      rh.ray.mask[k] = ~0u; rh.ray.id[k] = 0; rh.ray.flags[k] = 0;
      rh.hit.geomID[k] = RTC_INVALID_GEOMETRY_ID;
    }
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
    Packet<N>::intersect(valid, scene, &context, &rh);
    for (int k = 0; k < N; ++k) {
      if (!valid[k]) continue;
      const bool hit = rh.hit.geomID[k] != RTC_INVALID_GEOMETRY_ID;
      prim[pixel[k]] = hit ? int(rh.hit.primID[k]) : -1;
      depth[pixel[k]] = hit ? rh.ray.tfar[k] : -1.0f;
    }
  }
}

int run(const PeerOptions& o) {
  const Scene scene = loadGltfFile(o.scene);
  if (scene.triangleCount() == 0) throw SceneError("'" + o.scene + "' has no triangles");
  const Camera camera = scene.has_camera ? scene.camera : defaultCamera(sceneBounds(scene));
  CameraRayGenerator generator(camera, o.width, o.height);
  std::vector<GrRay> rays(size_t(o.width) * o.height);
  generator.centreWindow(PixelWindow{0, 0, o.width, o.height}, rays.data());

  omp_set_num_threads(o.threads);
  const std::string config = "threads=" + std::to_string(o.threads);
  RTCDevice device = rtcNewDevice(config.c_str());
  if (!device) throw RenderError("Embree: rtcNewDevice failed");
  Stopwatch clock;
  RTCScene rtc_scene = buildScene(device, scene);
  const double build_ms = clock.ms();
  if (rtcGetDeviceError(device) != RTC_ERROR_NONE) throw RenderError("Embree: scene build failed");

  std::vector<int> prim(rays.size(), -1);
  std::vector<float> depth(rays.size());
  std::vector<double> frame_ms;
  for (int f = 0; f <= o.frames; ++f) {  // frame 0 warms up
    clock.restart();
    if (o.packet == 1) traceSingle(rtc_scene, rays, prim, depth);
    else if (o.packet == 8) tracePackets<8>(rtc_scene, rays, o.width, o.height, prim, depth);
    else tracePackets<16>(rtc_scene, rays, o.width, o.height, prim, depth);
    if (f > 0) frame_ms.push_back(clock.ms());
  }
  const double frame_median = median(frame_ms);
  const long long hits = std::count_if(prim.begin(), prim.end(), [](int p) { return p >= 0; });
  if (!o.primid_path.empty()) {
    std::vector<float> ids(prim.begin(), prim.end());
    writeAov(o.primid_path, o.width, o.height, 1, ids);
  }
  if (!o.depth_path.empty()) writeAov(o.depth_path, o.width, o.height, 1, depth);
  rtcReleaseScene(rtc_scene);
  rtcReleaseDevice(device);
  std::printf("{\"build_ms\": %.4f, \"frame_ms\": %.4f, \"mrays_per_s\": %.4f, \"rays\": %zu, "
              "\"hits\": %lld, \"threads\": %d, \"packet\": %d, \"triangles\": %zu}\n",
              build_ms, frame_median, rays.size() / (frame_median * 1e3), rays.size(), hits,
              o.threads, o.packet, scene.triangleCount());
  return 0;
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
