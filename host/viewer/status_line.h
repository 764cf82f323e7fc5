// The viewer's status line (the window's title): what is shown and how fast it renders.
#pragma once
#include <cstdint>
#include <optional>
#include <string>

namespace gridrt {

struct FrameStatus {
  std::string scene, device, accel, view;
  size_t triangles = 0;
  int pes = 0;  // the grid's PEs (0 without a grid)
  // The last frame rendered: the loop's time for it (preparing the scene included), the
  // renderer's, its rays and its phases.
  double wall_ms = 0, frame_ms = 0;
  uint64_t rays = 0;
  double lists_ms = 0, kernel_ms = 0, phase2_ms = 0, shading_ms = 0;
  // The last change's grid and intersector (built again for each camera, as the command
  // line builds them for its camera), 0 when the last frame needed none.
  double setup_ms = 0;
  int samples = 0, target_samples = 1;  // progressive refinement: samples in, of --spp
  std::optional<double> time;           // the animation's time, if posed
  bool playing = false;
  std::string note;  // what the last key did, when it says something (a snapshot's file)
};

// "gridrt | SCENE | VIEW | F fps, M Mrays/s | lists L, kernels K, phase 2 P, shading S,
// setup U ms | T triangles, N PEs, ACCEL | DEVICE | sample s/n | t=T s (playing) | NOTE".
std::string statusLine(const FrameStatus& s);

}  // namespace gridrt
