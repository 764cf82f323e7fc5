// Embree 3 (Debian's libembree-dev) as a gridrt Intersector: the CPU peer GridRT is
// measured against. Plugged into gridrt's own Renderer, it traces a whole Whitted
// frame (camera, reflection, refraction and shadow rays) with the same shading around it,
// so that a frame can be compared with gridrt's frame and not only a camera-ray trace.
// Built only where CMake finds Embree (tools/setup.sh --bench); used by tools/embree_peer.
#pragma once
#include <embree3/rtcore.h>

#include <string>
#include <vector>

#include "intersector.h"
#include "scene.h"

namespace gridrt {

class EmbreeIntersector : public Intersector {
 public:
  // The scene's triangles as one geometry (primID = the global triangle index), Embree's
  // high-quality BVH built on `threads` threads. packet: 1 traces one ray at a time
  // (rtcIntersect1 / rtcOccluded1); 8 or 16 traces packets: camera rays in tiles of
  // 4 x (packet / 4) pixels, other batches in runs of `packet` consecutive rays (the
  // renderer spawns them in 4x4 pixel blocks, so a run comes from neighbouring pixels).
  EmbreeIntersector(const Scene& scene, int threads, int packet);
  ~EmbreeIntersector() override;
  EmbreeIntersector(const EmbreeIntersector&) = delete;
  EmbreeIntersector& operator=(const EmbreeIntersector&) = delete;

  std::string name() const override;
  double buildMs() const { return build_ms_; }

  // Closest hits; in AnyHit mode Embree's occlusion query, which does not say which
  // triangle occludes: an occluded ray reports triangle 0 at its tmax.
  void intersect(const std::vector<GrRay>& rays, HitMode mode, std::vector<GrHit>& hits,
                 RayDiagnostics* diagnostics) override;
  // Packets as tiles of the view's window (one ray at a time when packet is 1).
  void intersectPrimary(const PinholeView& view, const std::vector<GrRay>& rays,
                        std::vector<GrHit>& hits, RayDiagnostics* diagnostics) override;

 private:
  RTCDevice device_ = nullptr;
  RTCScene scene_ = nullptr;
  int packet_ = 1;
  double build_ms_ = 0.0;
};

}  // namespace gridrt
