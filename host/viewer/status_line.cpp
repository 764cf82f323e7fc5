#include "status_line.h"

#include <cstdio>

namespace gridrt {

std::string statusLine(const FrameStatus& s) {
  std::string line = "gridrt";
  if (!s.scene.empty()) line += " | " + s.scene;
  if (s.view.empty()) return line;
  char text[256];
  const double fps = s.wall_ms + s.setup_ms > 0 ? 1000.0 / (s.wall_ms + s.setup_ms) : 0.0;
  const double mrays = s.frame_ms > 0 ? double(s.rays) / (s.frame_ms * 1e3) : 0.0;
  std::snprintf(text, sizeof text,
                " | %s | %.1f fps, %.2f Mrays/s | lists %.1f, kernels %.1f, phase 2 %.1f, "
                "shading %.1f, setup %.1f ms | %zu triangles, %d PEs, %s | %s | sample %d/%d",
                s.view.c_str(), fps, mrays, s.lists_ms, s.kernel_ms, s.phase2_ms, s.shading_ms,
                s.setup_ms, s.triangles, s.pes, s.accel.c_str(), s.device.c_str(), s.samples,
                s.target_samples);
  line += text;
  if (s.time) {
    std::snprintf(text, sizeof text, " | t=%.3f s%s", *s.time, s.playing ? " (playing)" : "");
    line += text;
  }
  if (!s.note.empty()) line += " | " + s.note;
  return line;
}

}  // namespace gridrt
