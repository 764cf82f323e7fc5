// The intersector interface: every implementation (brute, dda, gridrt, reference) takes a
// batch of rays and returns, per ray, the closest hit in (tmin, tmax) — smallest t, and
// on equal t the lowest global triangle index — or, in AnyHit mode, some hit (shadows).
#pragma once
#include <cstdint>
#include <glm/glm.hpp>
#include <string>
#include <vector>

#include "camera_rays.h"
#include "gridrt_types.h"
#include "pinhole_view.h"

namespace gridrt {

enum class HitMode { Closest, AnyHit };

// How GridRT's PE kernels give a work-group's rays to its work-items: Packets, 16 rays in the
// float16 lanes of each work-item (a CPU device's SIMD: gridrt_lists.cl, gridrt_bundles.cl);
// Lanes, one ray a work-item (a GPU's: gridrt_lists_lanes.cl, gridrt_bundles_lanes.cl); Auto,
// Packets on a CPU device and Lanes on any other. The hits are the same.
enum class PeLayout { Auto, Packets, Lanes };

// How a GridRT batch's rays and results cross to the device and back: Map, the device's
// buffers mapped into host memory whole and written or read there (on a device that works
// in the host's memory, a CPU's, the buffers themselves: nothing copied); Copy, written
// into host arrays kept between batches and copied across, only the bytes the batch uses
// (for a GPU's own memory, where a mapping is a copy of the whole buffer). The hits are
// the same. Map is the default on every device: on PoCL's CPU device Copy adds its
// copies to the frame, and on a GPU the two are yet to be measured against each other
// (tools/gpu_check.sh runs both in turns).
enum class BatchTransfer { Map, Copy };

// Choices of the device kernels (the test and the layout are build-time) and of how their
// batches reach them.
struct KernelOptions {
  bool watertight = false;  // Woop-Benthin-Wald watertight test instead of Moeller-Trumbore
  PeLayout pe_layout = PeLayout::Auto;
  BatchTransfer transfer = BatchTransfer::Map;
  // The watertight test reads vertices, not edges (GrTriangle::vertex_layout).
  std::string defines() const { return watertight ? "-DGR_WATERTIGHT -DGR_TRIANGLE_VERTICES" : ""; }
};

// Work and time counted over all batches since the last reset.
struct IntersectCounters {
  uint64_t rays = 0;
  // Ray-triangle tests the rays' voxels hold: for gridrt each (ray, PE) pair tested (not
  // skipped by the interrupt) times the PE's triangles, the paper's count; for the others
  // the tests they ran.
  uint64_t tests = 0;
  uint64_t tests_run = 0;      // ray-triangle tests run (gridrt: those left after culling)
  uint64_t list_entries = 0;   // (ray, PE) pairs (gridrt)
  uint64_t skipped_pairs = 0;  // pairs skipped by the emulated interrupt
  uint64_t packets = 0;        // 16-lane packets the PE kernels ran (gridrt), padding included
  // The host's work before the kernels (gridrt), in three parts:
  double walk_ms = 0;          // the traversal lists' walk of the grid
  double binning_ms = 0;       // the (ray, PE) pairs binned by PE into the device's buffer
  double bundling_ms = 0;      // camera and light bundles, with the light's culling sets
  double kernel_ms = 0;        // upload + kernel + download
  double device_ms = 0;        // of which the PE kernels ran on the device (gridrt; profiling)
  double transfer_ms = 0;      // a batch's maps, unmaps and copies on the device (gridrt)
  double reduce_ms = 0;        // phase-2 reduction on the host
  uint64_t split_batches = 0;  // batches too large for the device, run in parts (gridrt)

  double listsMs() const { return walk_ms + binning_ms + bundling_ms; }
};

// Per-ray diagnostics for AOVs, filled when requested.
struct RayDiagnostics {
  std::vector<int> tests;        // tests of its PEs up to the winner (gridrt: ray_tests.h)
  std::vector<int> winning_pe;   // PE that produced the hit, -1 if none
  std::vector<int> list_length;  // number of PEs in the ray's traversal list
};

class Intersector {
 public:
  virtual ~Intersector() = default;
  virtual std::string name() const = 0;
  // hits is resized to rays.size(). diagnostics may be null.
  virtual void intersect(const std::vector<GrRay>& rays, HitMode mode, std::vector<GrHit>& hits,
                         RayDiagnostics* diagnostics) = 0;
  // Closest hits of primary rays from a pinhole camera (ray k = pixel k of view.window).
  // Intersectors that can exploit the camera's structure override it.
  virtual void intersectPrimary(const PinholeView& view, const std::vector<GrRay>& rays,
                                std::vector<GrHit>& hits, RayDiagnostics* diagnostics) {
    (void)view;
    intersect(rays, HitMode::Closest, hits, diagnostics);
  }
  // The same for rays it makes itself: the centre rays of view.window from `camera` into
  // `rays` (resized; ray k = pixel k, row-major), then their closest hits (through
  // intersectPrimary for a pinhole camera). Intersectors that can write the rays where
  // they need them while they make them override it.
  virtual void generateAndIntersectPrimary(const PinholeView& view,
                                           const CameraRayGenerator& camera,
                                           std::vector<GrRay>& rays, std::vector<GrHit>& hits,
                                           RayDiagnostics* diagnostics) {
    rays.resize(size_t(view.window.width()) * view.window.height());
    camera.centreWindow(view.window, rays.data());
    if (camera.pinhole())
      intersectPrimary(view, rays, hits, diagnostics);
    else
      intersect(rays, HitMode::Closest, hits, diagnostics);
  }
  // Rays that all end at `point` (shadow rays towards a point or spot light: origin, unit
  // direction to the point, tmax the distance). Intersectors that can exploit the common
  // end override it.
  virtual void intersectTowardsPoint(const glm::vec3& point, const std::vector<GrRay>& rays,
                                     HitMode mode, std::vector<GrHit>& hits) {
    (void)point;
    intersect(rays, mode, hits, nullptr);
  }
  IntersectCounters& counters() { return counters_; }

 protected:
  IntersectCounters counters_;
};

}  // namespace gridrt
