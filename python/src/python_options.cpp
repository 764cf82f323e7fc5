#include "python_options.h"

#include "errors.h"

namespace gridrt {

Options pythonOptions(const std::vector<std::string>& arguments) {
  // The image is an .exr's (float, linear), so what the command line allows only for one
  // (--crop-output window) is allowed here.
  std::vector<const char*> argv{"gridrt", "--quiet", "--format", "exr"};
  for (const std::string& a : arguments) argv.push_back(a.c_str());
  std::optional<Options> o = parseCommandLine(int(argv.size()), argv.data());
  if (!o) throw UsageError("--help and --version print: ask the gridrt command");
  if (o->list_devices) throw UsageError("list_devices: call gridrt.devices()");
  if (o->output_named || !o->aovs.empty() || !o->aov_file.empty() || !o->aov_layers.empty() ||
      !o->stats_json.empty() || o->stats || o->frames)
    throw UsageError("output, aov, aov_file, stats, stats_json and frames write files or "
                     "print: render() returns the image (use the gridrt command for files)");
  if (o->scene == "-") throw UsageError("a scene from standard input: pass a path or a Scene");
  return *o;
}

}  // namespace gridrt
