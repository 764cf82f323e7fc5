#include "view_command.h"

#include <cstdio>
#include <filesystem>
#include <sstream>

#include "standard_streams.h"

namespace gridrt {

namespace {

// %.9g: nine significant digits name every float uniquely, so the text parses back to it.
std::string floatText(float v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.9g", double(v));
  return text;
}
// %.17g does the same for a double.
std::string doubleText(double v) {
  char text[40];
  std::snprintf(text, sizeof text, "%.17g", v);
  return text;
}
std::string vec3Text(const glm::vec3& v) {
  return floatText(v.x) + "," + floatText(v.y) + "," + floatText(v.z);
}

// A word as a POSIX shell reads it back: as it is when it holds only safe characters,
// otherwise in single quotes.
std::string shellWord(const std::string& word) {
  bool safe = !word.empty();
  for (char c : word)
    safe = safe && (std::isalnum((unsigned char)c) || std::string("-_./,:=+%@").find(c) !=
                                                          std::string::npos);
  if (safe) return word;
  std::string quoted = "'";
  for (char c : word) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return quoted + "'";
}

Options defaults() {
  const char* argv[] = {"gridrt"};
  return *parseCommandLine(1, argv);
}

}  // namespace

std::string commandLineOf(const Options& o) {
  const Options d = defaults();
  std::ostringstream line;
  line << "gridrt";
  if (!o.scene.empty()) line << ' ' << shellWord(o.scene);
  line << " --width " << o.width << " --height " << o.height;
  auto option = [&](const char* flag, const std::string& value) {
    line << ' ' << flag << ' ' << shellWord(value);
  };
  if (o.accel != d.accel)
    option("--accel", o.accel == AccelKind::Dda     ? "dda"
                      : o.accel == AccelKind::Brute ? "brute"
                                                    : o.accel == AccelKind::Reference ? "reference"
                                                                                      : "gridrt");
  if (o.grid.automatic) {
    if (o.grid.structure != d.grid.structure)
      option("--grid", o.grid.structure == GridStructure::Adaptive ? "adaptive" : "uniform");
    if (o.grid.density != d.grid.density) option("--grid-density", floatText(o.grid.density));
  } else {
    option("--grid", std::to_string(o.grid.dims.x) + "," + std::to_string(o.grid.dims.y) + "," +
                         std::to_string(o.grid.dims.z));
  }
  if (o.watertight) option("--intersector", "watertight");
  if (o.spp != d.spp) option("--spp", std::to_string(o.spp));
  if (o.max_depth != d.max_depth) option("--max-depth", std::to_string(o.max_depth));
  if (o.primary_only) line << " --primary-only";
  if (o.shading != d.shading) option("--shading", o.shading == ShadingModel::Gltf ? "gltf" : "phong");
  if (o.background != d.background) option("--background", vec3Text(o.background));
  if (o.ambient != d.ambient) option("--ambient", floatText(o.ambient));
  if (o.ray_offset.robust != d.ray_offset.robust ||
      (!o.ray_offset.robust && o.ray_offset.epsilon != d.ray_offset.epsilon))
    option("--ray-offset",
           o.ray_offset.robust ? "robust" : "epsilon=" + floatText(o.ray_offset.epsilon));
  if (o.adaptive_aa) {
    option("--aa", "adaptive");
    if (o.aa_samples != d.aa_samples) option("--aa-samples", std::to_string(o.aa_samples));
    if (o.aa_threshold != d.aa_threshold) option("--aa-threshold", floatText(o.aa_threshold));
  }
  if (o.min_path_weight != d.min_path_weight)
    option("--min-path-weight", floatText(o.min_path_weight));
  if (o.alpha) line << " --alpha";
  if (!o.camera_name.empty()) option("--camera", o.camera_name);
  if (o.eye) option("--look-at", vec3Text(*o.eye) + ":" + vec3Text(*o.target));
  if (o.fov_degrees) option("--fov", floatText(*o.fov_degrees));
  if (o.time) option("--time", doubleText(*o.time));
  if (!o.animation.empty()) option("--animation", o.animation);
  return line.str();
}

std::string snapshotPath(const Options& o, const std::string& folder) {
  const std::string stem = o.scene.empty() || o.scene == kStandardInput
                               ? "gridrt"
                               : std::filesystem::path(o.scene).stem().string();
  std::error_code ec;
  for (int n = 0;; ++n) {
    char name[32];
    std::snprintf(name, sizeof name, "_view_%04d.png", n);
    const std::filesystem::path path = std::filesystem::path(folder) / (stem + name);
    if (!std::filesystem::exists(path, ec)) return folder == "." ? stem + name : path.string();
  }
}

}  // namespace gridrt
