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
  std::vector<std::string> candidates = moduleSearchPaths(
      GRIDRT_IMAGE_CODEC_FILE, GRIDRT_MODULE_DIR_FROM_BIN, GRIDRT_IMAGE_CODEC_PATH);
  // Beside the shared object that holds this code, when it is not the executable (the
  // Python module's extension: python/CMakeLists.txt installs the module beside it),
  // before the build's own path.
  Dl_info self{};
  if (dladdr(reinterpret_cast<void*>(&loadCodec), &self) && self.dli_fname &&
      fs::path(self.dli_fname).is_absolute())
    candidates.insert(candidates.end() - 1,
                      (fs::path(self.dli_fname).parent_path() / GRIDRT_IMAGE_CODEC_FILE).string());
  std::string why;
  if (void* entry = loadModuleEntry(candidates, GRIDRT_IMAGE_CODEC_ENTRY, why))
    return reinterpret_cast<const ImageCodec* (*)()>(entry)();
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
