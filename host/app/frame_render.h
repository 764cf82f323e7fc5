// One frame job's render, the command line's and the Python module's (python/): the scene
// prepared with the options' intersector, rendered 1 + --repeat times through the frame
// loop (host/render/renderer.h), its statistics; and the image its -o file holds.
#pragma once
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cl_runtime.h"
#include "frame_statistics.h"
#include "intersector.h"
#include "layered_image.h"
#include "options.h"
#include "renderer.h"
#include "scene.h"

namespace gridrt {

// Per-frame timings of the timed frames, and the intersector counters of the first.
struct FrameTimings {
  FramePhaseTimes phases;
  std::vector<double> kernel_ms, device_ms, transfer_ms, lists_ms, walk_ms, binning_ms, bundling_ms,
      reduce_ms;
  IntersectCounters first_frame_counters;
};

// One frame job's render: what it made, and its statistics (the keys of --stats-json
// that belong to a frame).
struct FrameResult {
  Frame frame;
  FrameTimings timings;
  nlohmann::json stats;
  double setup_ms = 0;         // the intersector: kernels (built once a run) and scene upload
  uint64_t split_batches = 0;  // batches of the first rendering split to fit the device
  std::string accel;
};

// Prepares the scene's triangles, builds its grid and intersector (the runtime keeps the
// programs it built, so only the first frame of a run compiles or loads them) and renders
// 1 + --repeat frames. With report_choices, prints what was chosen first (-v).
FrameResult renderScene(const Options& o, ClRuntime& runtime, const Scene& scene,
                        const Camera& camera, const std::function<void(double)>& progress,
                        bool report_choices);

// An image of the film's pixels as its file holds it under --crop: the renderer's film
// holds the window's pixels (the whole image without --crop); with --crop-output full
// they are placed in a full-size image, `outside` (black, or an AOV's miss value) around
// them; with window, the window alone at its offset in the file's data window.
LayeredImage croppedImage(const Options& o, LayeredImage image, float outside);

// The -o image of a frame: its film's R, G, B (and A), cropped as above.
LayeredImage outputImage(const Options& o, const Frame& frame);

}  // namespace gridrt
