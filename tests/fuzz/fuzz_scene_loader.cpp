// libFuzzer target: any byte string handed to the glTF loader must either load or be
// refused with a one-line gridrt::SceneError. Every other exception, crash, leak or
// sanitizer report is a finding (frozen in tests/fuzz/regressions/).
#include <cstddef>
#include <cstdint>

#include "errors.h"
#include "gltf_loader.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  try {
    // No base directory: a fuzz input must never read a file from disk.
    gridrt::loadGltfFromMemory(data, size, "", "fuzz");
  } catch (const gridrt::SceneError&) {
    // The documented way to refuse bad input.
  }
  return 0;
}
