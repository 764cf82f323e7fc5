#include "options.h"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <filesystem>
#include <iostream>
#include <regex>
#include <set>
#include <sstream>

#include "aov_channels.h"
#include "build_identity.h"
#include "errors.h"
#include "image_format.h"
#include "standard_streams.h"

namespace gridrt {

namespace {

// The checks of every numeric option, one message each kind of mistake:
// "expected an integer in 1..4096, got '1.5'", "expected a finite number in 0..1, got 'nan'".
CLI::Validator integerIn(long lo, long hi) {
  const std::string range = std::to_string(lo) + ".." + std::to_string(hi);
  return CLI::Validator(
      [=](std::string& text) -> std::string {
        size_t used = 0;
        long v = 0;
        try {
          v = std::stol(text, &used);
        } catch (const std::exception&) {
          used = 0;
        }
        if (used == 0 || used != text.size()) return "expected an integer, got '" + text + "'";
        if (v < lo || v > hi) return "expected an integer in " + range + ", got '" + text + "'";
        return "";
      },
      range);
}

std::string formatNumber(double v) {
  std::ostringstream out;
  out << v;
  return out.str();
}

CLI::Validator numberIn(double lo, double hi) {
  const std::string range = formatNumber(lo) + ".." + formatNumber(hi);
  return CLI::Validator(
      [=](std::string& text) -> std::string {
        size_t used = 0;
        double v = 0;
        try {
          v = std::stod(text, &used);
        } catch (const std::exception&) {
          used = 0;
        }
        if (used == 0 || used != text.size()) return "expected a number, got '" + text + "'";
        if (!std::isfinite(v) || v < lo || v > hi)
          return "expected a finite number in " + range + ", got '" + text + "'";
        return "";
      },
      range);
}

glm::vec3 parseVec3(const std::string& flag, const std::string& text) {
  static const std::regex three(R"(^\s*([^,]+),([^,]+),([^,]+)\s*$)");
  std::smatch m;
  glm::vec3 v;
  try {
    if (!std::regex_match(text, m, three)) throw std::invalid_argument(text);
    for (int i = 0; i < 3; ++i) {
      size_t used = 0;
      v[i] = std::stof(m[i + 1].str(), &used);
      if (used != size_t(m[i + 1].length()) || !std::isfinite(v[i]))
        throw std::invalid_argument(text);
    }
  } catch (const std::exception&) {
    throw UsageError(flag + ": expected X,Y,Z (three finite numbers), got '" + text + "'");
  }
  return v;
}

void parseGrid(const std::string& text, GridSettings& grid) {
  // auto: the default structure; adaptive / uniform pick one (adaptive_grid.h).
  if (text == "auto" || text == "adaptive" || text == "uniform") {
    grid.automatic = true;
    grid.structure = text == "auto"       ? GridStructure::WhereNeeded
                     : text == "adaptive" ? GridStructure::Adaptive
                                          : GridStructure::Uniform;
    return;
  }
  static const std::regex dims(R"(^(\d{1,4}),(\d{1,4}),(\d{1,4})$)");
  std::smatch m;
  if (!std::regex_match(text, m, dims))
    throw UsageError("--grid: expected 'auto' or NX,NY,NZ, got '" + text + "'");
  glm::ivec3 n(std::stoi(m[1]), std::stoi(m[2]), std::stoi(m[3]));
  for (int a = 0; a < 3; ++a)
    if (n[a] < 1 || n[a] > kMaxGridResolution)
      throw UsageError("--grid: each resolution must be in 1.." +
                       std::to_string(kMaxGridResolution) + ", got '" + text + "'");
  grid.automatic = false;
  grid.dims = n;
}

void parseRayOffset(const std::string& text, RayOffset& offset) {
  if (text == "robust") {
    offset.robust = true;
    return;
  }
  static const std::regex eps(R"(^epsilon=(.+)$)");
  std::smatch m;
  float e = -1.0f;
  if (std::regex_match(text, m, eps)) {
    try {
      size_t used = 0;
      e = std::stof(m[1].str(), &used);
      if (used != size_t(m[1].length())) e = -1.0f;
    } catch (const std::exception&) {
      e = -1.0f;
    }
  }
  if (!(e >= 0.0f) || !std::isfinite(e))
    throw UsageError("--ray-offset: expected 'robust' or 'epsilon=E' with E >= 0, got '" + text +
                     "'");
  offset.robust = false;
  offset.epsilon = e;
}

struct RawOptions {
  std::string accel = "gridrt", grid = "auto", background, ray_offset = "robust", look_at;
  std::string crop, crop_output = "full", intersector = "mt", aa = "uniform", frames;
  std::string shading = "phong", format, pe_layout = "auto";
  std::string transfer = "map";
  std::vector<std::string> aovs;
  std::set<std::string> given;  // the options on the command line, e.g. "--spp"
};

// Options that only mean something beside another, refused alone instead of ignored.
// An option that changes nothing beside another is warned about, and the statistics say
// what was rendered.
void checkCombinations(Options& o, const RawOptions& raw) {
  auto given = [&](const char* flag) { return raw.given.count(flag) > 0; };
  if (o.adaptive_aa && given("--spp") && o.spp != 1) {
    o.warnings.push_back("--spp " + std::to_string(o.spp) +
                         " has no effect with --aa adaptive, which takes a centre sample and "
                         "--aa-samples more where neighbours differ");
    o.spp = 1;
  }
  for (const char* flag : {"--aa-samples", "--aa-threshold"})
    if (given(flag) && !o.adaptive_aa)
      throw UsageError(std::string(flag) + ": only with --aa adaptive");
  if (given("--grid-density") && !o.grid.automatic)
    throw UsageError(
        "--grid-density: only with --grid auto (an explicit --grid fixes the "
        "resolution)");
  if (given("--crop-output") && !o.crop) throw UsageError("--crop-output: only with --crop");
  if (o.verbose && o.quiet) throw UsageError("--verbose and --quiet: choose one");
  if (o.time && o.frames) throw UsageError("--time: not with --frames (which sets each frame's)");
  if (given("--fps") && !o.frames) throw UsageError("--fps: only with --frames");
  if (given("--animation") && !o.time && !o.frames)
    throw UsageError("--animation: only with --time or --frames");
  if (given("--pe-layout") && o.accel != AccelKind::GridRt)
    throw UsageError("--pe-layout: only with --accel gridrt (its PE kernels)");
  if (given("--transfer") && o.accel != AccelKind::GridRt)
    throw UsageError("--transfer: only with --accel gridrt (its batches)");
  const bool has_pes = o.accel == AccelKind::GridRt || o.accel == AccelKind::Dda;
  std::vector<std::string> names = o.aov_layers;
  for (const auto& aov : o.aovs) names.push_back(aov.first);
  for (const std::string& name : names)
    if (!has_pes && (name == "pe" || name == "listlen"))
      throw UsageError("--aov " + name +
                       ": only the grid intersectors (--accel gridrt, "
                       "dda) have PEs and traversal lists");
}

// --view shows one picture in a window and writes SCENE_view_NNNN.png on P: the options
// for files, sequences and timing runs have no place beside it.
void checkViewCombinations(const Options& o, const RawOptions& raw) {
  if (!o.view) return;
  for (const char* flag : {"--output", "--format", "--force", "--frames", "--fps", "--crop",
                           "--aov", "--aov-file", "--repeat", "--stats", "--stats-json",
                           "--list-devices"})
    if (raw.given.count(flag))
      throw UsageError(std::string("--view: not with ") + (std::string(flag) == "--output" ? "-o" : flag) +
                       " (P writes the view to SCENE_view_NNNN.png)");
  if (o.scene == kStandardInput)
    throw UsageError("--view: the scene must be a file (P prints a command that reads it again)");
}

// With --frames every image path is a frame pattern (without -o, SCENE_%04d.png); without
// it a path is taken as written, '%' and all, which is said when it looks like a pattern.
void checkFramePatterns(Options& o) {
  if (!o.frames) {
    if (FramePattern::isPattern(o.output))
      o.warnings.push_back("-o '" + o.output +
                           "' looks like a frame pattern but there is no --frames: it is the "
                           "file's name as written");
    return;
  }
  if (!o.output_named) {
    const std::filesystem::path derived(o.output);
    o.output =
        (derived.parent_path() / derived.stem()).string() + "_%04d" + derived.extension().string();
  }
  FramePattern("-o", o.output);
  for (const auto& aov : o.aovs) FramePattern("--aov " + aov.first, aov.second);
  if (!o.aov_file.empty()) FramePattern("--aov-file", o.aov_file);
}

// -o - writes the image to standard output in --format (png unless named), and nothing
// else may go there. A named file's format is its extension's, which --format must name
// too; without -o the derived name takes --format's extension.
void finishOutputFormat(Options& o, const RawOptions& raw) {
  if (!raw.format.empty()) o.format = formatNamed(raw.format);
  for (const auto& aov : o.aovs)
    if (aov.second == kStandardOutput)
      throw UsageError("--aov " + aov.first + ": only -o can write to standard output (-)");
  if (o.output == kStandardOutput) {
    if (!o.format) o.format = ImageFormat::Png;
    if (o.frames) throw UsageError("-o -: standard output takes one image, not --frames");
    if (o.stats_json == kStandardOutput)
      throw UsageError(
          "--stats-json -: standard output carries the image (-o -); write the statistics to "
          "a file");
    return;
  }
  if (!o.format) return;
  if (!o.output_named) {
    o.output = std::filesystem::path(o.output).replace_extension(formatName(*o.format)).string();
    return;
  }
  if (formatOfPath(o.output) != o.format)
    throw UsageError("--format " + raw.format + ": -o '" + o.output +
                     "' has another extension (drop --format, or name a ." + formatName(*o.format) +
                     " file)");
}

// --alpha needs an image format with an alpha channel; an unknown format is refused on
// its own when the output is checked.
void checkAlphaFormat(const Options& o) {
  if (!o.alpha) return;
  const std::optional<ImageFormat> format = o.format ? o.format : formatOfPath(o.output);
  if (!format || hasAlpha(*format)) return;
  const std::string shown =
      o.output == kStandardOutput ? "standard output" : "-o '" + o.output + "'";
  throw UsageError("--alpha: " + shown + " is " + formatName(*format) +
                   ", which has no alpha channel (write .png, .exr or .tif)");
}

// Two outputs on one path would leave only the last: refused.
void checkDistinctOutputs(const Options& o) {
  namespace fs = std::filesystem;
  std::vector<std::pair<std::string, std::string>> outputs;
  if (o.output != kStandardOutput) outputs.emplace_back("-o", o.output);
  for (const auto& aov : o.aovs) outputs.emplace_back("--aov " + aov.first, aov.second);
  if (!o.aov_file.empty()) outputs.emplace_back("--aov-file", o.aov_file);
  if (!o.stats_json.empty()) outputs.emplace_back("--stats-json", o.stats_json);
  std::error_code ec;
  auto key = [&](const std::string& path) {
    return fs::weakly_canonical(fs::absolute(path, ec), ec).string();
  };
  for (size_t i = 0; i < outputs.size(); ++i)
    for (size_t j = 0; j < i; ++j)
      if (key(outputs[i].second) == key(outputs[j].second))
        throw UsageError(outputs[i].first + ": writes '" + outputs[i].second + "', the file " +
                         outputs[j].first + " writes");
}

void buildApp(CLI::App& app, Options& o, RawOptions& raw) {
  app.description(
      "GridRT: a Whitted ray tracer on OpenCL, with the GridRT parallel architecture\n"
      "(uniform grid, one processing element per non-empty voxel, two-phase reduction).\n"
      "Without SCENE it renders the built-in default scene.");
  app.add_option("scene", o.scene,
                 "glTF 2.0 scene (.gltf or .glb), or a mesh: OBJ, PLY, STL, ... (assimp); - reads "
                 "a .gltf or .glb from standard input");
  app.add_option("-o,--output", o.output,
                 "output image: .png/.jpg (sRGB), .exr (linear) or - (standard output); "
                 "default SCENE.png (the scene's name, here), else gridrt.png");
  app.add_option("--format", raw.format,
                 "png, jpg or exr: of -o - (default png) or the default name; -o FILE's must "
                 "match it")
      ->check(CLI::IsMember({"png", "jpg", "jpeg", "exr"}));
  app.add_flag("--force", o.force, "without -o, replace an existing SCENE.png");
  app.add_flag("--alpha", o.alpha,
               "add alpha: each pixel's share of camera samples that hit (.png, .exr, .tif; "
               ".exr/.tif colour premultiplied)");
  app.add_option("--width", o.width, "image width in pixels")
      ->capture_default_str()
      ->check(integerIn(1, 65536));
  app.add_option("--height", o.height, "image height in pixels")
      ->capture_default_str()
      ->check(integerIn(1, 65536));
  app.add_option("--spp", o.spp, "samples per pixel (jittered when > 1)")
      ->capture_default_str()
      ->check(integerIn(1, 4096));
  app.add_option("--max-depth", o.max_depth, "reflection/refraction bounces")
      ->capture_default_str()
      ->check(integerIn(0, 64));
  app.add_option("--device", o.device, "OpenCL device: P:D or part of its name (default: first)");
  app.add_flag("--list-devices", o.list_devices, "list OpenCL devices and exit");
  app.add_flag("--view", o.view,
               "open a window that renders the scene live (mouse and keys: docs/viewer.md; "
               "P writes SCENE_view_NNNN.png)");
  app.add_option("--threads", o.threads, "threads for the host and a CPU device (0: all cores)")
      ->capture_default_str()
      ->check(integerIn(0, 4096));
  app.add_option("--wave-rays", o.wave_rays,
                 "camera rays a wave of the frame holds at most (whole rows; same image)")
      ->capture_default_str()
      ->check(integerIn(1, int(kMaxBatchRays)));
  app.add_option("--accel", raw.accel,
                 "intersector: gridrt, dda, brute (device) or reference (host, double)")
      ->capture_default_str()
      ->check(CLI::IsMember({"gridrt", "dda", "brute", "reference"}));
  app.add_option("--grid", raw.grid,
                 "grid: auto (adaptive if a voxel is full), adaptive, uniform or NX,NY,NZ")
      ->capture_default_str();
  app.add_option("--grid-density", o.grid.density,
                 "lambda of the auto (top) grid resolution R_i = d_i*cbrt(lambda*N/V)")
      ->capture_default_str()
      ->check(numberIn(0.001, 1000.0));
  app.add_flag("--pe-interrupt", o.pe_interrupt,
               "gridrt: in every batch a PE skips rays an earlier PE has hit (the paper's "
               "interrupt; camera rays always use it)");
  app.add_option("--pe-layout", raw.pe_layout,
                 "gridrt's PE kernels: packets (16 rays in each work-item's SIMD lanes), lanes "
                 "(a ray a work-item) or auto (packets on a CPU device, lanes on others)")
      ->capture_default_str()
      ->check(CLI::IsMember({"auto", "packets", "lanes"}));
  app.add_option("--transfer", raw.transfer,
                 "gridrt's batches: map (the device's buffers mapped whole) or copy (only the "
                 "bytes used, from and to host arrays)")
      ->capture_default_str()
      ->check(CLI::IsMember({"map", "copy"}));
  app.add_flag("--primary-only", o.primary_only,
               "primary rays only, headlight shading (the paper's measurement)");
  app.add_option("--aov", raw.aovs,
                 "NAME=FILE (repeatable; .exr): depth, primid, normal, geonormal, albedo, "
                 "tests, pe, listlen; NAME alone: a layer of --aov-file")
      ->type_name("NAME[=FILE]")
      ->expected(1)  // one value per --aov (the help shows no "..."), so a scene may follow
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll)
      ->allow_extra_args(false);
  app.add_option("--aov-file", o.aov_file,
                 "one .exr with the image and the AOVs as layers (depth.Z, primid.id, ...): "
                 "the bare --aov NAMEs, else depth, primid, normal, geonormal, albedo")
      ->type_name("FILE");
  app.add_option("--repeat", o.repeat, "render N more frames after the first, for timing")
      ->capture_default_str()
      ->check(integerIn(0, 100000));
  app.add_option("--stats-json", o.stats_json,
                 "write statistics as JSON to FILE (- for standard output)");
  app.add_flag("--stats", o.stats, "print a statistics table");
  app.add_flag("-q,--quiet", o.quiet, "print nothing but errors");
  app.add_flag("-v,--verbose", o.verbose, "print what was chosen: camera, lights, grid, passes");
  app.add_option("--background", raw.background, "background colour R,G,B (linear)");
  app.add_option("--ambient", o.ambient, "ambient factor (times diffuse albedo)")
      ->capture_default_str()
      ->check(numberIn(0.0, 1000.0));
  app.add_option("--ray-offset", raw.ray_offset,
                 "secondary ray origins: robust (scale-aware) or epsilon=E")
      ->capture_default_str();
  app.add_option("--intersector", raw.intersector,
                 "ray/triangle test: mt (Moeller-Trumbore) or watertight (Woop et al. 2013)")
      ->capture_default_str()
      ->check(CLI::IsMember({"mt", "watertight"}));
  app.add_option("--shading", raw.shading,
                 "lights: phong (the paper's) or gltf (glTF metallic-roughness BRDF)")
      ->capture_default_str()
      ->check(CLI::IsMember({"phong", "gltf"}));
  app.add_option("--aa", raw.aa,
                 "anti-aliasing: uniform (--spp samples) or adaptive (centres, then "
                 "--aa-samples more where neighbours differ by > --aa-threshold)")
      ->capture_default_str()
      ->check(CLI::IsMember({"uniform", "adaptive"}));
  app.add_option("--aa-samples", o.aa_samples, "adaptive: extra samples per refined pixel")
      ->capture_default_str()
      ->check(integerIn(1, 4096));
  app.add_option("--aa-threshold", o.aa_threshold,
                 "adaptive: largest neighbour difference (linear, any channel) left alone")
      ->capture_default_str()
      ->check(numberIn(0.0, 1000.0));
  app.add_option("--min-path-weight", o.min_path_weight,
                 "adaptive depth: skip bounces whose throughput is below this (0: never)")
      ->capture_default_str()
      ->check(numberIn(0.0, 1.0));
  app.add_option("--camera", o.camera_name,
                 "use the glTF camera with this name, or the N-th in the scene (from 0)");
  app.add_option("--look-at", raw.look_at, "EX,EY,EZ:TX,TY,TZ camera eye and target");
  app.add_option("--fov", o.fov_degrees, "vertical field of view in degrees")
      ->check(numberIn(0.01, 179.0));
  app.add_option("--crop", raw.crop,
                 "X0,Y0,X1,Y1 render only pixels [X0,X1) x [Y0,Y1) (tiles: gridrt-merge-tiles)");
  app.add_option("--crop-output", raw.crop_output,
                 "with --crop: full (full-size image, zero outside) or window (.exr/.tif only, "
                 "offset kept in the data window)")
      ->capture_default_str()
      ->check(CLI::IsMember({"full", "window"}));
  app.add_option("--time", o.time, "pose the scene's animations at T seconds")
      ->type_name("T")
      ->check(numberIn(0.0, 1e6));
  app.add_option("--frames", raw.frames,
                 "frames A..B at frame/--fps s into -o PATTERN (out_%04d.png; --aov too)")
      ->type_name("A:B");
  app.add_option("--fps", o.fps, "frames per second of --frames")
      ->type_name("F")
      ->capture_default_str()
      ->check(numberIn(0.001, 1e6));
  app.add_option("--animation", o.animation, "play only this glTF animation (default: all)")
      ->type_name("NAME|INDEX");
  // The build's identity is computed only when asked for (build_identity.h).
  app.set_version_flag("--version", [] { return versionText(GRIDRT_VERSION); });
}

// --aov NAME=FILE: the AOV's own file; --aov NAME: a layer of --aov-file, which without
// any holds every AOV but the diagnostics.
void parseAovs(Options& o, const RawOptions& raw) {
  for (const auto& spec : raw.aovs) {
    size_t eq = spec.find('=');
    std::string name = eq == std::string::npos ? spec : spec.substr(0, eq);
    if (eq + 1 == spec.size() || !isAovName(name))
      throw UsageError(
          "--aov: expected NAME=FILE or NAME with NAME one of depth, primid, normal, geonormal, "
          "albedo, tests, pe, listlen; got '" +
          spec + "'");
    if (eq != std::string::npos)
      o.aovs.emplace_back(name, spec.substr(eq + 1));
    else if (std::find(o.aov_layers.begin(), o.aov_layers.end(), name) == o.aov_layers.end())
      o.aov_layers.push_back(name);
  }
  if (o.aov_file.empty()) {
    if (!o.aov_layers.empty())
      throw UsageError("--aov " + o.aov_layers.front() +
                       ": without =FILE only with --aov-file, whose layer it is");
    return;
  }
  if (o.aov_file == kStandardOutput)
    throw UsageError("--aov-file: only -o can write to standard output (-)");
  if (formatOfPath(o.aov_file) != ImageFormat::Exr)
    throw UsageError("--aov-file: '" + o.aov_file +
                     "' is not an .exr file (only OpenEXR holds layers of floats and integers)");
  if (o.aov_layers.empty())
    o.aov_layers.assign(std::begin(kLayerAovNames), std::end(kLayerAovNames));
}

void finishCrop(Options& o, const RawOptions& raw) {
  o.crop_output = raw.crop_output == "window" ? CropOutput::Window : CropOutput::Full;
  if (raw.crop.empty()) return;
  o.crop = parseCropWindow(raw.crop, o.width, o.height);
  // A window alone must say where it lies, which only formats with a data window can.
  const std::optional<ImageFormat> format = o.format ? o.format : formatOfPath(o.output);
  if (o.crop_output == CropOutput::Window && !(format && keepsDataWindow(*format)))
    throw UsageError(
        "--crop-output window: the output must be .exr, .tif or .tiff (the "
        "window's offset is kept in the file's data window), got '" +
        o.output + "'");
}

void finish(Options& o, const RawOptions& raw) {
  o.accel = raw.accel == "dda"         ? AccelKind::Dda
            : raw.accel == "brute"     ? AccelKind::Brute
            : raw.accel == "reference" ? AccelKind::Reference
                                       : AccelKind::GridRt;
  parseGrid(raw.grid, o.grid);
  parseRayOffset(raw.ray_offset, o.ray_offset);
  o.watertight = raw.intersector == "watertight";
  o.pe_layout = raw.pe_layout == "packets" ? PeLayout::Packets
                : raw.pe_layout == "lanes" ? PeLayout::Lanes
                                           : PeLayout::Auto;
  o.transfer = raw.transfer == "copy" ? BatchTransfer::Copy : BatchTransfer::Map;
  o.shading = raw.shading == "gltf" ? ShadingModel::Gltf : ShadingModel::Phong;
  o.adaptive_aa = raw.aa == "adaptive";
  if (!raw.background.empty()) o.background = parseVec3("--background", raw.background);
  if (!raw.look_at.empty()) {
    size_t colon = raw.look_at.find(':');
    if (colon == std::string::npos)
      throw UsageError("--look-at: expected EX,EY,EZ:TX,TY,TZ, got '" + raw.look_at + "'");
    o.eye = parseVec3("--look-at", raw.look_at.substr(0, colon));
    o.target = parseVec3("--look-at", raw.look_at.substr(colon + 1));
    if (*o.eye == *o.target) throw UsageError("--look-at: eye and target are the same point");
  }
  if (!raw.frames.empty()) o.frames = parseFrameRange(raw.frames);
  parseAovs(o, raw);
  finishOutputFormat(o, raw);
  finishCrop(o, raw);
  checkAlphaFormat(o);
  checkCombinations(o, raw);
  checkViewCombinations(o, raw);
  checkFramePatterns(o);
  checkDistinctOutputs(o);
}

}  // namespace

std::optional<Options> parseCommandLine(int argc, const char* const* argv) {
  Options o;
  RawOptions raw;
  CLI::App app{"", "gridrt"};
  buildApp(app, o, raw);
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp&) {
    std::cout << app.help();
    return std::nullopt;
  } catch (const CLI::CallForVersion&) {
    std::cout << app.version() << '\n';
    return std::nullopt;
  } catch (const CLI::ParseError& e) {
    std::string what = e.what();
    std::replace(what.begin(), what.end(), '\n', ' ');
    throw UsageError(what + " (see gridrt --help)");
  }
  o.size_given = app.count("--width") > 0 || app.count("--height") > 0;
  o.output_named = app.count("--output") > 0;
  if (!o.output_named && !o.scene.empty() && o.scene != kStandardInput)
    o.output = std::filesystem::path(o.scene).stem().string() + ".png";
  for (const CLI::Option* option : app.get_options())
    if (option->count() > 0) raw.given.insert(option->get_name());
  finish(o, raw);
  return o;
}

std::string helpText() {
  Options o;
  RawOptions raw;
  CLI::App app{"", "gridrt"};
  buildApp(app, o, raw);
  return app.help();
}

}  // namespace gridrt
