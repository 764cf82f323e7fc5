// Where a dlopen-ed module of gridrt's is looked for, in this order: beside the running
// executable (build/gridrt, or a copy moved with its module), in the installed modules'
// folder relative to the executable (bin/../lib/gridrt: cmake/install.cmake's
// GRIDRT_MODULE_DIR_FROM_BIN), then where the build put it (the tests' own executables,
// which run from another folder of the build tree). Nothing depends on the working
// directory, and an installed tree finds its modules wherever it is moved. The image codec
// and the viewer's window module are both found and loaded by the functions below.
#pragma once
#include <dlfcn.h>

#include <filesystem>
#include <string>
#include <system_error>
#include <vector>

namespace gridrt {

// The candidate paths of module `file`, best first; `dirFromExecutable` is relative to the
// executable's folder, `buildPath` absolute.
inline std::vector<std::string> moduleSearchPaths(const std::string& file,
                                                  const std::string& dirFromExecutable,
                                                  const std::string& buildPath) {
  namespace fs = std::filesystem;
  std::vector<std::string> paths;
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    paths.push_back((exe.parent_path() / file).string());
    paths.push_back((exe.parent_path() / dirFromExecutable / file).lexically_normal().string());
  }
  paths.push_back(buildPath);
  return paths;
}

// Symbol `entry` of the first of `candidates` that exists, loads and has it; the module
// stays loaded for the life of the process. Null if none does, with `why` saying what the
// last one that exists lacked (empty when none exists).
inline void* loadModuleEntry(const std::vector<std::string>& candidates, const char* entry,
                             std::string& why) {
  why.clear();
  std::error_code ec;
  for (const std::string& path : candidates) {
    if (!std::filesystem::exists(path, ec)) continue;
    void* module = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!module) {
      why = dlerror();
      continue;
    }
    if (void* symbol = dlsym(module, entry)) return symbol;
    why = path + ": no " + entry;
  }
  return nullptr;
}

}  // namespace gridrt
