#include "scene_queries.h"

#include <cmath>
#include <limits>
#include <string>

#include "errors.h"
#include "prepared_triangles.h"
#include "python_options.h"
#include "scene_source.h"

namespace gridrt {

namespace {

// A miss's t: no distance, so +inf (numpy's comparisons and minimum treat it as farthest).
constexpr float kMissT = std::numeric_limits<float>::infinity();

bool finite3(const float* v) {
  return std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]);
}

// The hit's barycentrics (u, v: of the intersector's second and third vertex, which
// prepareTriangles puts in canonical order) as those of the triangle's second and third
// vertex in the scene's order. A kept triangle's vertices are distinct (it has an area).
void toSceneOrder(const Scene& scene, GrHit& hit, int triangle) {
  const glm::vec3* given = &scene.positions[size_t(triangle) * 3];
  glm::vec3 canonical[3];
  canonicalVertices(given, canonical);
  const float weight[3] = {1.0f - hit.u - hit.v, hit.u, hit.v};
  float in_scene_order[3] = {0.0f, 0.0f, 0.0f};
  for (int c = 0; c < 3; ++c)
    for (int k = 0; k < 3; ++k)
      if (canonical[c] == given[k]) in_scene_order[k] = weight[c];
  hit.u = in_scene_order[1];
  hit.v = in_scene_order[2];
}

}  // namespace

void checkRays(const RayArrays& rays) {
  auto row = [](size_t i) { return "row " + std::to_string(i); };
  for (size_t i = 0; i < rays.count; ++i) {
    if (!finite3(rays.origins + 3 * i))
      throw UsageError("origins: " + row(i) + " holds a NaN or infinite value");
    const float* d = rays.directions + 3 * i;
    if (!finite3(d)) throw UsageError("directions: " + row(i) + " holds a NaN or infinite value");
    if (d[0] == 0.0f && d[1] == 0.0f && d[2] == 0.0f)
      throw UsageError("directions: " + row(i) + " is zero");
    const float tmax = rays.tmax ? rays.tmax[i] : rays.tmax_all;
    if (!(tmax > 0.0f))
      throw UsageError("tmax: " + (rays.tmax ? row(i) + " is " : std::string("is ")) +
                       std::to_string(tmax) + ", not a positive number");
  }
}

SceneQueries::SceneQueries(Scene scene, std::vector<int32_t> face_of, std::string device)
    : scene_(std::move(scene)), face_of_(std::move(face_of)), device_(std::move(device)) {}

Intersector& SceneQueries::intersector() {
  if (!prepared_) {
    // The command line's defaults (grid auto, gridrt, Moeller-Trumbore) on this device.
    const Options o = pythonOptions({"--device", device_});
    runtime_ = std::make_unique<ClRuntime>(o.device);
    const Camera camera = chooseCamera(o, scene_, sceneBounds(scene_));
    prepared_ = std::make_unique<PreparedScene>(o, *runtime_, scene_, camera);
  }
  return prepared_->intersector();
}

void SceneQueries::trace(const RayArrays& rays, HitMode mode, GrHit* hits) {
  checkRays(rays);
  std::lock_guard<std::mutex> lock(mutex_);
  Intersector& engine = intersector();
  std::vector<GrRay>& batch = batch_;
  std::vector<GrHit>& found = found_;
  for (size_t first = 0; first < rays.count; first += kQueryBatchRays) {
    const size_t n = std::min(kQueryBatchRays, rays.count - first);
    batch.resize(n);
    for (size_t k = 0; k < n; ++k) {
      const float* o = rays.origins + 3 * (first + k);
      const float* d = rays.directions + 3 * (first + k);
      batch[k] = GrRay{o[0], o[1], o[2], 0.0f,
                       d[0], d[1], d[2], rays.tmax ? rays.tmax[first + k] : rays.tmax_all};
    }
    engine.intersect(batch, mode, found, nullptr);
    for (size_t k = 0; k < n; ++k) {
      GrHit h = found[k];
      if (h.prim < 0) {
        h = GrHit{kMissT, -1, 0.0f, 0.0f};
      } else {
        toSceneOrder(scene_, h, h.prim);
        if (!face_of_.empty()) h.prim = face_of_[size_t(h.prim)];
      }
      hits[first + k] = h;
    }
  }
}

}  // namespace gridrt
