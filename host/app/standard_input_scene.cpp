#include "standard_input_scene.h"

#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <vector>

#include "errors.h"

namespace gridrt {

namespace {

constexpr const char* kLabel = "standard input";

[[noreturn]] void refuse(const std::string& reason) {
  throw SceneError(std::string(kLabel) + ": " + reason);
}

std::vector<unsigned char> readAll(std::FILE* in) {
  std::vector<unsigned char> bytes;
  unsigned char chunk[1 << 16];
  size_t got = 0;
  while ((got = std::fread(chunk, 1, sizeof chunk, in)) > 0)
    bytes.insert(bytes.end(), chunk, chunk + got);
  if (std::ferror(in)) refuse(std::string("cannot read: ") + std::strerror(errno));
  return bytes;
}

}  // namespace

GltfDocument readStandardInputScene() {
  if (::isatty(STDIN_FILENO))
    refuse("is a terminal; pipe a .gltf or .glb into 'gridrt -' (gridrt - < scene.glb)");
  const std::vector<unsigned char> bytes = readAll(stdin);
  if (bytes.empty()) refuse("no scene (it is empty); pipe a .gltf or .glb into 'gridrt -'");
  return GltfDocument::fromMemory(bytes.data(), bytes.size(), ".", kLabel);
}

}  // namespace gridrt
