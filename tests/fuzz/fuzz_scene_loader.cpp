// libFuzzer target: any byte string handed to the glTF loader must either load (and pose
// its animations) or be refused with a one-line gridrt::SceneError. Every other exception, crash,
// leak or sanitizer report is a finding (frozen in tests/fuzz/regressions/).
#include <cstddef>
#include <cstdint>

#include "animated_scene.h"
#include "errors.h"
#include "gltf_loader.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  try {
    // No base directory: a fuzz input must never read a file from disk.
    const gridrt::GltfDocument document = gridrt::GltfDocument::fromMemory(data, size, "", "fuzz");
    document.flatten();
    // Its animations, posed before, between and after their keys.
    if (!document.model().animations.empty()) {
      const gridrt::AnimatedScene animated(document, {}, "");
      for (double t : {-1.0, 0.0, 0.37, 1e9}) animated.at(t);
    }
  } catch (const gridrt::SceneError&) {
    // The documented way to refuse bad input.
  }
  return 0;
}
