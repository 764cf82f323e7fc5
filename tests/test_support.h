// Helpers shared by the tests: paths of the source tree, the shared scenes and the binary.
#pragma once
#include <string>

namespace gridrt::test {

std::string sourcePath(const std::string& relative);  // <repo>/relative
std::string sharedScene(const std::string& name);     // <repo>/../shared/scenes/name
std::string gridrtBinary();                           // build/gridrt
std::string tempPath(const std::string& name);        // a fresh path under a per-test temp dir
bool fileExists(const std::string& path);

}  // namespace gridrt::test
