#include "image_module.h"

#include <dlfcn.h>

#include <filesystem>
#include <string>
#include <vector>

#include "errors.h"
#include "module_search.h"

namespace gridrt {
namespace {

namespace fs = std::filesystem;

const ImageCodec* loadCodec() {
  const std::vector<std::string> candidates = moduleSearchPaths(
      GRIDRT_IMAGE_CODEC_FILE, GRIDRT_MODULE_DIR_FROM_BIN, GRIDRT_IMAGE_CODEC_PATH);
  std::string why;
  std::error_code ec;
  for (const std::string& path : candidates) {
    if (!fs::exists(path, ec)) continue;
    void* module = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!module) {
      why = dlerror();
      continue;
    }
    auto entry = reinterpret_cast<const ImageCodec* (*)()>(dlsym(module, GRIDRT_IMAGE_CODEC_ENTRY));
    if (entry) return entry();
    why = path + ": no " + GRIDRT_IMAGE_CODEC_ENTRY;
  }
  if (why.empty())
    why = "not found beside the executable, in its " GRIDRT_MODULE_DIR_FROM_BIN
          " nor at " GRIDRT_IMAGE_CODEC_PATH;
  throw RenderError("cannot load the image module " GRIDRT_IMAGE_CODEC_FILE ": " + why);
}

}  // namespace

const ImageCodec& imageCodec() {
  // Loaded once, on the first image read or written; the module stays for the process.
  static const ImageCodec* const codec = loadCodec();
  return *codec;
}

}  // namespace gridrt
