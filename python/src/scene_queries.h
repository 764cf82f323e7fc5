// A scene as the Python module holds it, and its ray queries (Scene.intersect, .occluded):
// the scene, the device its queries run on, and the GridRT intersector the command line
// would build for it (PreparedScene: the same grid and kernels), made on the first query
// and kept. Rays are traced in batches of at most kQueryBatchRays, each split further by
// the intersector where the device needs it.
#pragma once
#include <cstddef>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "cl_runtime.h"
#include "gridrt_types.h"
#include "intersector.h"
#include "prepared_scene.h"
#include "scene.h"

namespace gridrt {

// Rays handed to the intersector at once: bounds the host's copy of them (32 bytes a ray)
// and of their hits (16 bytes), and keeps a batch within the frame loop's largest.
constexpr size_t kQueryBatchRays = size_t(1) << 20;

// count rays: origins and directions count x 3 floats, row-major; tmax one a ray, or null
// for tmax_all on every ray. They start at t = 0 (the ray's origin).
struct RayArrays {
  const float* origins = nullptr;
  const float* directions = nullptr;
  const float* tmax = nullptr;
  float tmax_all = 0.0f;
  size_t count = 0;
};

// Throws UsageError naming the first bad ray: a NaN or infinite origin or direction, a
// zero direction, a tmax that is NaN or not positive (+inf is allowed).
void checkRays(const RayArrays& rays);

class SceneQueries {
 public:
  // face_of: per triangle of scene, the id hits report (empty: the triangle's own global
  // index, as the primid AOV numbers it). device: as --device.
  SceneQueries(Scene scene, std::vector<int32_t> face_of, std::string device);

  const Scene& scene() const { return scene_; }
  const std::string& device() const { return device_; }
  size_t triangleCount() const { return scene_.triangleCount(); }

  // Per ray of `rays` (checked) its closest hit (Closest) or some hit (AnyHit) into
  // hits[0..count): t, the prim id (-1: none), the barycentrics u, v. Safe to call without
  // Python's lock: one query at a time runs on a scene.
  void trace(const RayArrays& rays, HitMode mode, GrHit* hits);

 private:
  Intersector& intersector();  // built on first use

  Scene scene_;
  std::vector<int32_t> face_of_;
  std::string device_;
  std::mutex mutex_;
  std::unique_ptr<ClRuntime> runtime_;
  std::unique_ptr<PreparedScene> prepared_;
  // A batch's rays and hits, kept between queries (their pages stay mapped).
  std::vector<GrRay> batch_;
  std::vector<GrHit> found_;
};

}  // namespace gridrt
