#include "standard_input_scene.h"

#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <iostream>
#include <vector>

#include "errors.h"
#include "file_bytes.h"

namespace gridrt {

namespace {

constexpr const char* kLabel = "standard input";

[[noreturn]] void refuse(const std::string& reason) {
  throw SceneError(std::string(kLabel) + ": " + reason);
}

}  // namespace

GltfDocument readStandardInputScene() {
  if (::isatty(STDIN_FILENO))
    refuse("is a terminal; pipe a .gltf or .glb into 'gridrt -' (gridrt - < scene.glb)");
  std::vector<unsigned char> bytes;
  if (!readStreamBytes(std::cin, bytes))
    refuse(std::string("cannot read: ") + std::strerror(errno));
  if (bytes.empty()) refuse("no scene (it is empty); pipe a .gltf or .glb into 'gridrt -'");
  return GltfDocument::fromMemory(bytes.data(), bytes.size(), ".", kLabel);
}

}  // namespace gridrt
