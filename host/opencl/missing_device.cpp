#include "missing_device.h"

#include <cstdlib>
#include <filesystem>
#include <system_error>

namespace gridrt {

namespace fs = std::filesystem;

namespace {

std::string envOr(const char* name, const std::string& fallback) {
  const char* v = std::getenv(name);
  return v && *v ? std::string(v) : fallback;
}

// The installed OpenCL drivers: the ICD loader's vendor files.
bool anyDriverInstalled() {
  std::error_code ec;
  const fs::path vendors = envOr("OCL_ICD_VENDORS", "/etc/OpenCL/vendors");
  if (fs::is_regular_file(vendors, ec)) return true;
  for (const auto& entry : fs::directory_iterator(vendors, ec))
    if (entry.path().extension() == ".icd") return true;
  return false;
}

// Whether the folder exists or can be made, and a file can be made in it.
bool canWriteFolder(const fs::path& folder) {
  std::error_code ec;
  fs::create_directories(folder, ec);
  if (!fs::is_directory(folder, ec)) return false;
  const fs::path probe = folder / ".gridrt-write-probe";
  FILE* f = std::fopen(probe.c_str(), "w");
  if (!f) return false;
  std::fclose(f);
  fs::remove(probe, ec);
  return true;
}

}  // namespace

std::string poclCacheDir() {
  if (const char* dir = std::getenv("POCL_CACHE_DIR"); dir && *dir) return dir;
  const std::string xdg = envOr("XDG_CACHE_HOME", envOr("HOME", "") + "/.cache");
  return xdg + "/pocl";
}

std::string missingDeviceMessage(size_t platforms) {
  const std::string what =
      platforms == 0 ? "no OpenCL platform found" : "no OpenCL device found on any platform";
  if (!anyDriverInstalled())
    return what + ": install an OpenCL driver, e.g. 'apt-get install pocl-opencl-icd'";
  const std::string cache = poclCacheDir();
  if (!canWriteFolder(cache))
    return what + ": PoCL cannot write its kernel cache folder '" + cache +
           "' (POCL_CACHE_DIR): point POCL_CACHE_DIR at a writable folder";
  return what + ": an OpenCL driver is installed but reported none; POCL_DEBUG=all (PoCL) " +
         "says why";
}

}  // namespace gridrt
