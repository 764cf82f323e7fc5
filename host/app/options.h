// Everything the command line can set, with its default. main() only parses these and
// hands them to the application (host/app/application.cpp).
#pragma once
#include <glm/glm.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "crop_window.h"
#include "frame_sequence.h"
#include "gltf_brdf.h"
#include "image_format.h"
#include "intersector.h"
#include "renderer.h"
#include "uniform_grid.h"
#include "whitted_shading.h"

namespace gridrt {

enum class AccelKind { GridRt, Dda, Brute, Reference };

struct Options {
  std::string scene;  // glTF/glb path; "-" standard input; empty = the built-in default scene
  // PNG/JPEG (sRGB) or EXR (linear) by extension; "-": standard output, in `format`.
  // Without -o: the scene's name with .png (--format's extension) in the current folder
  // (gridrt.png for the built-in scene and a scene read from standard input), never
  // replacing a file unless --force.
  std::string output = "gridrt.png";
  std::optional<ImageFormat> format;  // --format; always set for -o - (default png)
  bool output_named = false;          // -o given: the user asked for that file, existing or not
  bool force = false;                 // --force: a derived output may replace an existing file
  // --alpha: the image gets an alpha channel, each pixel's share of camera samples that hit
  // the scene (png, exr, tif only); the colour is associated with it (docs/output.md).
  bool alpha = false;
  int width = 640;
  int height = 480;
  // --width or --height given: the image keeps that size. Otherwise a scene camera's
  // aspectRatio sets the width (height 480), as its author framed it.
  bool size_given = false;
  int spp = 1;
  int max_depth = 5;
  std::string device;  // "" first device, "P:D", or a name substring
  int threads = 0;     // --threads: host loops and the CPU device; 0 = every core
  // --wave-rays: camera rays (pixels x samples) a wave of the frame holds at most, in whole
  // rows; the image is the same bit for bit whatever the size (renderer.h).
  int wave_rays = int(kMaxPassRays);
  bool list_devices = false;
  // --view: an interactive window instead of an image file (host/viewer, docs/viewer.md).
  bool view = false;
  AccelKind accel = AccelKind::GridRt;
  GridSettings grid;                            // --grid auto | NX,NY,NZ; --grid-density
  bool pe_interrupt = false;                    // emulate the paper's interrupt on the device
  PeLayout pe_layout = PeLayout::Auto;          // --pe-layout: gridrt's PE kernels
  BatchTransfer transfer = BatchTransfer::Map;  // --transfer: how gridrt's batches cross
  bool primary_only = false;                    // primary rays, headlight shading
  std::vector<std::pair<std::string, std::string>> aovs;  // NAME=FILE
  // --aov-file FILE.exr: the image and the AOVs aov_layers names (bare --aov NAME; without
  // one, kLayerAovNames) as the layers of one OpenEXR file.
  std::string aov_file;
  std::vector<std::string> aov_layers;
  int repeat = 0;          // extra timed frames after the first
  std::string stats_json;  // write statistics as JSON here
  bool stats = false;      // print a statistics table
  bool quiet = false;
  bool verbose = false;  // -v: what was chosen (choices_report.h)
  glm::vec3 background{0.0f};
  float ambient = 0.05f;
  RayOffset ray_offset;
  ShadingModel shading = ShadingModel::Phong;  // --shading phong | gltf
  bool watertight = false;                     // --intersector watertight (default mt)
  bool adaptive_aa = false;                    // --aa adaptive (default uniform --spp)
  int aa_samples = 8;                          // extra samples of a refined pixel
  float aa_threshold = 0.1f;                   // neighbour difference that triggers refinement
  float min_path_weight = 0.0f;                // adaptive depth: 0 traces every bounce
  std::string camera_name;                     // pick a glTF camera by name
  std::optional<glm::vec3> eye, target;        // --look-at overrides
  std::optional<float> fov_degrees;            // --fov override (vertical, degrees)
  std::optional<PixelWindow> crop;             // --crop: render only this window of the image
  CropOutput crop_output = CropOutput::Full;   // --crop-output full | window
  std::vector<std::string> warnings;           // options that have no effect, said once
  // Animation (docs/animation.md): one time (--time), or frames first..last at
  // frame / fps seconds (--frames, --fps) into -o and --aov paths that are frame patterns
  // (frame_sequence.h); neither: the scene's still pose, as written.
  std::optional<double> time;
  std::optional<FrameRange> frames;
  double fps = 24.0;
  std::string animation;  // --animation NAME|INDEX: the one that plays (default all)
};

// Parses argv. Returns nullopt when --help or --version was handled (printed, exit 0).
// Throws UsageError with a one-line message for anything malformed.
std::optional<Options> parseCommandLine(int argc, const char* const* argv);

// The --help text (the README's CLI reference is generated from it).
std::string helpText();

}  // namespace gridrt
