#include "choices_report.h"

#include <algorithm>
#include <cstdio>

namespace gridrt {

namespace {

std::string formatted(const char* format, double a, double b = 0.0) {
  char text[64];
  std::snprintf(text, sizeof text, format, a, b);
  return text;
}

std::string counted(size_t n, const std::string& thing) {
  return std::to_string(n) + " " + thing + (n == 1 ? "" : "s");
}

const char* accelName(AccelKind kind) {
  switch (kind) {
    case AccelKind::GridRt:
      return "gridrt";
    case AccelKind::Dda:
      return "dda";
    case AccelKind::Brute:
      return "brute";
    case AccelKind::Reference:
      return "reference";
  }
  return "?";
}

}  // namespace

std::vector<std::string> choicesReport(const Options& o, const Scene& scene, const Camera& camera,
                                       const UniformGrid* grid, double build_ms) {
  std::vector<std::string> lines;
  lines.push_back(
      "scene: " +
      (o.scene.empty() ? std::string("the built-in default scene") : "'" + o.scene + "'") + ", " +
      std::to_string(scene.triangleCount()) + " triangles, " +
      counted(scene.materials.size(), "material") + ", " +
      (scene.has_lights ? counted(scene.lights.size(), "light")
                        : std::string("no lights: a key and a fill light added")));
  std::string view = scene.has_camera || o.eye ? "'" + camera.name + "'" : "the default";
  if (!scene.has_camera && !o.eye) view += " three-quarter view of the scene's box";
  view += camera.orthographic
              ? formatted(", orthographic, half height %g", camera.ymag)
              : formatted(", perspective, %.1f degrees vertical", camera.yfov * 57.29577951308232);
  lines.push_back("camera: " + view + ", " + std::to_string(o.width) + "x" +
                  std::to_string(o.height));
  if (grid) {
    int fullest = 0;
    for (int pe = 0; pe < grid->peCount(); ++pe)
      fullest = std::max(fullest, grid->triangleCountOfPe(pe));
    const std::string dims = std::to_string(grid->info.nx) + "x" + std::to_string(grid->info.ny) +
                             "x" + std::to_string(grid->info.nz);
    lines.push_back(
        "grid: " +
        (grid->adaptive.empty()
             ? "uniform " + dims
             : "adaptive over " + dims + ", " + counted(grid->adaptive.depth, "level") + " below") +
        ", " + std::to_string(grid->peCount()) + " PEs (at most " + std::to_string(fullest) +
        " triangles), built in " + formatted("%.1f ms", build_ms));
  }
  lines.push_back(std::string("render: ") + accelName(o.accel) + ", " +
                  (o.primary_only ? "primary rays, headlight shading"
                                  : "Whitted, up to " + std::to_string(o.max_depth) + " bounces") +
                  ", " +
                  (o.adaptive_aa
                       ? "adaptive anti-aliasing"
                       : std::to_string(o.spp) + " sample" + (o.spp > 1 ? "s" : "") + " a pixel"));
  return lines;
}

}  // namespace gridrt
