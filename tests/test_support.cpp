#include "test_support.h"

#include <unistd.h>

#include <filesystem>

namespace gridrt::test {

std::string sourcePath(const std::string& relative) {
  return std::string(GRIDRT_SOURCE_DIR) + "/" + relative;
}

std::string sharedScene(const std::string& name) {
  return std::string(GRIDRT_SHARED_SCENES) + "/" + name;
}

std::string gridrtBinary() { return GRIDRT_BINARY; }

std::string tempPath(const std::string& name) {
  auto dir = std::filesystem::temp_directory_path() /
             ("gridrt_test_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  return (dir / name).string();
}

bool fileExists(const std::string& path) { return std::filesystem::exists(path); }

}  // namespace gridrt::test
