// A scene made ready to render with the options' intersector: its triangles, its grid (for
// gridrt and dda, built for the camera's ray origins) and the intersector holding the scene
// on the device. The command line prepares one per frame job and renders 1 + --repeat
// frames through it; the viewer and the Python module keep one across many frames and
// cameras, each frame a Renderer over it (host/render/renderer.h), the same frame loop.
#pragma once
#include <memory>
#include <vector>

#include "cl_runtime.h"
#include "gridrt_intersector.h"
#include "intersector.h"
#include "options.h"
#include "renderer.h"
#include "scene.h"
#include "uniform_grid.h"

namespace gridrt {

// The renderer's settings the options ask for (AOVs and diagnostics only when an output
// wants them: filling them costs time per frame).
RenderSettings renderSettings(const Options& o);

class PreparedScene {
 public:
  // Builds the grid and the intersector (the runtime keeps the programs it built, so only
  // its first PreparedScene compiles or loads them). OpenCL errors become RenderErrors.
  PreparedScene(const Options& o, ClRuntime& runtime, const Scene& scene, const Camera& camera);
  // The same for rays that start anywhere in `ray_origins` (GridSettings::ray_origins): the
  // viewer builds one for a box its camera moves in. Any such box gives the same hits: the
  // grid's margin only grows with it.
  PreparedScene(const Options& o, ClRuntime& runtime, const Scene& scene,
                const Bounds& ray_origins);
  // The intersector holds the grid and triangles by reference: the object stays put.
  PreparedScene(const PreparedScene&) = delete;
  PreparedScene& operator=(const PreparedScene&) = delete;

  Intersector& intersector() { return *intersector_; }
  // The GridRT intersector (null for the other --accel kinds), for its own statistics.
  GridRtIntersector* gridrt() { return gridrt_; }
  // The grid (null unless --accel gridrt or dda).
  const UniformGrid* grid() const { return uses_grid_ ? &grid_ : nullptr; }
  double buildMs() const { return build_ms_; }  // the grid's build
  double setupMs() const { return setup_ms_; }  // the intersector: kernels and scene upload

 private:
  std::vector<GrTriangle> triangles_;
  UniformGrid grid_;
  bool uses_grid_ = false;
  std::unique_ptr<Intersector> intersector_;
  GridRtIntersector* gridrt_ = nullptr;
  double build_ms_ = 0, setup_ms_ = 0;
};

}  // namespace gridrt
