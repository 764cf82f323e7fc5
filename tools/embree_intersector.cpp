#include "embree_intersector.h"

#include <algorithm>

#include "errors.h"
#include "parallel_loops.h"
#include "pinhole_view.h"
#include "stopwatch.h"

namespace gridrt {

namespace {

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

GrHit missOf(const GrRay& r) { return GrHit{r.tmax, -1, 0.0f, 0.0f}; }

// An occluded ray (AnyHit): Embree does not say by which triangle (intersector header).
GrHit occludedOf(const GrRay& r) { return GrHit{r.tmax, 0, 0.0f, 0.0f}; }

// One ray as Embree's single-ray query takes it.
RTCRay embreeRay(const GrRay& r) {
  RTCRay ray;
  ray.org_x = r.ox;
  ray.org_y = r.oy;
  ray.org_z = r.oz;
  ray.tnear = r.tmin;
  ray.dir_x = r.dx;
  ray.dir_y = r.dy;
  ray.dir_z = r.dz;
  ray.time = 0.0f;
  ray.tfar = r.tmax;
  ray.mask = ~0u;
  ray.id = 0;
  ray.flags = 0;
  return ray;
}

// One ray at a time, closest hits (rtcIntersect1) or occlusion (rtcOccluded1).
void traceSingle(RTCScene scene, const std::vector<GrRay>& rays, HitMode mode, GrHit* hits) {
  const long long n = (long long)rays.size();
  if (mode == HitMode::AnyHit) {
    parallelForDynamic(0LL, (long long)(n), 1024LL, [&](long long i) {
      const GrRay& r = rays[i];
      RTCIntersectContext context;
      rtcInitIntersectContext(&context);
      RTCRay ray = embreeRay(r);
      rtcOccluded1(scene, &context, &ray);
      hits[i] = ray.tfar < 0.0f ? occludedOf(r) : missOf(r);  // tfar = -inf: occluded
    });
    return;
  }
  parallelForDynamic(0LL, (long long)(n), 1024LL, [&](long long i) {
    const GrRay& r = rays[i];
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRayHit rh;
    rh.ray = embreeRay(r);
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(scene, &context, &rh);
    hits[i] = rh.hit.geomID == RTC_INVALID_GEOMETRY_ID
                  ? missOf(r)
                  : GrHit{rh.ray.tfar, int(rh.hit.primID), rh.hit.u, rh.hit.v};
  });
}

// The packet types and calls of one width.
template <int N>
struct Packet;
template <>
struct Packet<8> {
  using RayHit = RTCRayHit8;
  static void intersect(const int* valid, RTCScene s, RTCIntersectContext* c, RayHit* rh) {
    rtcIntersect8(valid, s, c, rh);
  }
  static void occluded(const int* valid, RTCScene s, RTCIntersectContext* c, RayHit* rh) {
    rtcOccluded8(valid, s, c, &rh->ray);
  }
};
template <>
struct Packet<16> {
  using RayHit = RTCRayHit16;
  static void intersect(const int* valid, RTCScene s, RTCIntersectContext* c, RayHit* rh) {
    rtcIntersect16(valid, s, c, rh);
  }
  static void occluded(const int* valid, RTCScene s, RTCIntersectContext* c, RayHit* rh) {
    rtcOccluded16(valid, s, c, &rh->ray);
  }
};

// Rays index[0 .. N) of `rays` (-1: an empty lane) as one packet; their hits into `hits`.
template <int N>
void tracePacket(RTCScene scene, const GrRay* rays, const long long* index, HitMode mode,
                 bool coherent, GrHit* hits) {
  alignas(64) int valid[N];
  alignas(64) typename Packet<N>::RayHit rh;
  for (int k = 0; k < N; ++k) {
    valid[k] = index[k] >= 0 ? -1 : 0;
    const GrRay& r = rays[valid[k] ? index[k] : index[0]];
    rh.ray.org_x[k] = r.ox;
    rh.ray.org_y[k] = r.oy;
    rh.ray.org_z[k] = r.oz;
    rh.ray.dir_x[k] = r.dx;
    rh.ray.dir_y[k] = r.dy;
    rh.ray.dir_z[k] = r.dz;
    rh.ray.tnear[k] = r.tmin;
    rh.ray.tfar[k] = r.tmax;
    rh.ray.time[k] = 0.0f;
    rh.ray.mask[k] = ~0u;
    rh.ray.id[k] = 0;
    rh.ray.flags[k] = 0;
    rh.hit.geomID[k] = RTC_INVALID_GEOMETRY_ID;
  }
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  context.flags =
      coherent ? RTC_INTERSECT_CONTEXT_FLAG_COHERENT : RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT;
  if (mode == HitMode::AnyHit)
    Packet<N>::occluded(valid, scene, &context, &rh);
  else
    Packet<N>::intersect(valid, scene, &context, &rh);
  for (int k = 0; k < N; ++k) {
    if (!valid[k]) continue;
    const GrRay& r = rays[index[k]];
    GrHit& hit = hits[index[k]];
    if (mode == HitMode::AnyHit)
      hit = rh.ray.tfar[k] < 0.0f ? occludedOf(r) : missOf(r);
    else
      hit = rh.hit.geomID[k] == RTC_INVALID_GEOMETRY_ID
                ? missOf(r)
                : GrHit{rh.ray.tfar[k], int(rh.hit.primID[k]), rh.hit.u[k], rh.hit.v[k]};
  }
}

// Runs of N consecutive rays.
template <int N>
void traceRuns(RTCScene scene, const std::vector<GrRay>& rays, HitMode mode, GrHit* hits) {
  const long long n = (long long)rays.size(), runs = (n + N - 1) / N;
  parallelForDynamic(0LL, (long long)(runs), 16LL, [&](long long run) {
    long long index[N];
    for (int k = 0; k < N; ++k) index[k] = run * N + k < n ? run * N + k : -1;
    tracePacket<N>(scene, rays.data(), index, mode, false, hits);
  });
}

// Tiles of 4 x (N / 4) pixels of a window whose ray k is pixel k, row-major.
template <int N>
void traceTiles(RTCScene scene, const std::vector<GrRay>& rays, int width, int height,
                GrHit* hits) {
  constexpr int kTileW = 4, kTileH = N / 4;
  const int tiles_x = (width + kTileW - 1) / kTileW, tiles_y = (height + kTileH - 1) / kTileH;
  parallelForDynamic(0LL, (long long)(tiles_x * tiles_y), 16LL, [&](long long tile) {
    const int x0 = int(tile % tiles_x) * kTileW, y0 = int(tile / tiles_x) * kTileH;
    long long index[N];
    for (int k = 0; k < N; ++k) {
      const int x = x0 + k % kTileW, y = y0 + k / kTileW;
      index[k] = x < width && y < height ? (long long)y * width + x : -1;
    }
    tracePacket<N>(scene, rays.data(), index, HitMode::Closest, true, hits);
  });
}

}  // namespace

EmbreeIntersector::EmbreeIntersector(const Scene& scene, int threads, int packet)
    : packet_(packet) {
  if (packet != 1 && packet != 8 && packet != 16)
    throw RenderError("Embree: packet size " + std::to_string(packet) + " is not 1, 8 or 16");
  const std::string config = "threads=" + std::to_string(threads);
  device_ = rtcNewDevice(config.c_str());
  if (!device_) throw RenderError("Embree: rtcNewDevice failed");
  Stopwatch clock;
  scene_ = buildScene(device_, scene);
  build_ms_ = clock.ms();
  if (rtcGetDeviceError(device_) != RTC_ERROR_NONE) {
    rtcReleaseScene(scene_);
    rtcReleaseDevice(device_);
    throw RenderError("Embree: scene build failed");
  }
}

EmbreeIntersector::~EmbreeIntersector() {
  rtcReleaseScene(scene_);
  rtcReleaseDevice(device_);
}

std::string EmbreeIntersector::name() const {
  return packet_ == 1 ? "embree 1-ray" : "embree " + std::to_string(packet_) + "-ray packets";
}

void EmbreeIntersector::intersect(const std::vector<GrRay>& rays, HitMode mode,
                                  std::vector<GrHit>& hits, RayDiagnostics* diagnostics) {
  (void)diagnostics;  // Embree counts no tests
  hits.resize(rays.size());
  counters_.rays += rays.size();
  if (packet_ == 8) return traceRuns<8>(scene_, rays, mode, hits.data());
  if (packet_ == 16) return traceRuns<16>(scene_, rays, mode, hits.data());
  traceSingle(scene_, rays, mode, hits.data());
}

void EmbreeIntersector::intersectPrimary(const PinholeView& view, const std::vector<GrRay>& rays,
                                         std::vector<GrHit>& hits, RayDiagnostics* diagnostics) {
  if (packet_ == 1) return intersect(rays, HitMode::Closest, hits, diagnostics);
  hits.resize(rays.size());
  counters_.rays += rays.size();
  const int w = view.window.width(), h = view.window.height();
  if (packet_ == 8) return traceTiles<8>(scene_, rays, w, h, hits.data());
  traceTiles<16>(scene_, rays, w, h, hits.data());
}

}  // namespace gridrt
