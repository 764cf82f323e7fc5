#include "cl_runtime.h"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <optional>
#include <regex>
#include <sstream>

#include "errors.h"
#include "missing_device.h"

namespace gridrt {

const char* embeddedKernelSource(const std::string& name);  // generated at build time

namespace {

std::string deviceTypeName(cl_device_type type) {
  if (type & CL_DEVICE_TYPE_GPU) return "GPU";
  if (type & CL_DEVICE_TYPE_CPU) return "CPU";
  if (type & CL_DEVICE_TYPE_ACCELERATOR) return "accelerator";
  return "other";
}

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  return s;
}

std::string trim(const std::string& s) {
  size_t b = s.find_first_not_of(" \t\n\r");
  size_t e = s.find_last_not_of(" \t\n\r");
  return b == std::string::npos ? "" : s.substr(b, e - b + 1);
}

std::vector<cl::Platform> platformsOrEmpty() {
  // PoCL's CPU device pins its worker threads to cores with POCL_AFFINITY=1 (read when
  // the platform starts); unpinned, they sometimes share a core with each other or with
  // the host's threads. Pinned, small primary frames (bunny_res4 320x240) are faster, the
  // large and Whitted frames unchanged (docs/history.md). A value the user set is kept.
  setenv("POCL_AFFINITY", "1", /*overwrite=*/0);
  std::vector<cl::Platform> platforms;
  try {
    cl::Platform::get(&platforms);
  } catch (const cl::Error&) {
    platforms.clear();  // CL_PLATFORM_NOT_FOUND_KHR: no ICD installed
  }
  return platforms;
}

DeviceInfo describe(const cl::Platform& platform, const cl::Device& device, int p, int d) {
  DeviceInfo info;
  info.platform_index = p;
  info.device_index = d;
  info.platform_name = trim(platform.getInfo<CL_PLATFORM_NAME>());
  info.name = trim(device.getInfo<CL_DEVICE_NAME>());
  info.type = deviceTypeName(device.getInfo<CL_DEVICE_TYPE>());
  info.compute_units = device.getInfo<CL_DEVICE_MAX_COMPUTE_UNITS>();
  info.max_work_group_size = device.getInfo<CL_DEVICE_MAX_WORK_GROUP_SIZE>();
  info.local_mem_bytes = device.getInfo<CL_DEVICE_LOCAL_MEM_SIZE>();
  info.global_mem_bytes = device.getInfo<CL_DEVICE_GLOBAL_MEM_SIZE>();
  info.max_alloc_bytes = device.getInfo<CL_DEVICE_MAX_MEM_ALLOC_SIZE>();
  info.correctly_rounded_div_sqrt =
      (device.getInfo<CL_DEVICE_SINGLE_FP_CONFIG>() & CL_FP_CORRECTLY_ROUNDED_DIVIDE_SQRT) != 0;
  return info;
}

std::string oneLine(std::string text) {
  std::replace(text.begin(), text.end(), '\n', ' ');
  return text;
}

}  // namespace

std::vector<DeviceInfo> listDevices() {
  std::vector<DeviceInfo> out;
  auto platforms = platformsOrEmpty();
  for (size_t p = 0; p < platforms.size(); ++p) {
    std::vector<cl::Device> devices;
    try {
      platforms[p].getDevices(CL_DEVICE_TYPE_ALL, &devices);
    } catch (const cl::Error&) {
      continue;  // a platform without devices
    }
    for (size_t d = 0; d < devices.size(); ++d)
      out.push_back(describe(platforms[p], devices[d], int(p), int(d)));
  }
  return out;
}

std::string formatDeviceTable(const std::vector<DeviceInfo>& devices) {
  std::ostringstream os;
  char line[512];
  std::snprintf(line, sizeof line, "%-5s %-6s %-46s %5s %8s %10s %10s\n", "P:D", "type", "name",
                "CUs", "max WG", "local KiB", "global MiB");
  os << line;
  for (const auto& d : devices) {
    std::snprintf(line, sizeof line, "%d:%-3d %-6s %-46.46s %5u %8zu %10llu %10llu\n",
                  d.platform_index, d.device_index, d.type.c_str(), d.name.c_str(), d.compute_units,
                  d.max_work_group_size, d.local_mem_bytes / 1024,
                  d.global_mem_bytes / (1024 * 1024));
    os << line;
  }
  return os.str();
}

// A header that is not embedded keeps its #include line: harmless inside a disabled #ifdef,
// and reported by the OpenCL compiler if it is really needed.
std::string assembleKernelSource(const std::string& file) {
  const char* text = embeddedKernelSource(file);
  if (!text) throw RenderError("kernel source '" + file + "' is not embedded in this build");
  static const std::regex include_line(R"(^\s*#\s*include\s*"([^"]+)\"\s*$)");
  std::istringstream in(text);
  std::ostringstream out;
  std::string line;
  int line_number = 0;
  while (std::getline(in, line)) {
    ++line_number;
    std::smatch m;
    if (std::regex_match(line, m, include_line) && embeddedKernelSource("common/" + m[1].str())) {
      // Headers are guarded, so including one twice is harmless. The generated source
      // starts with '#line 1', so the line after the include is line_number here.
      out << assembleKernelSource("common/" + m[1].str()) << "\n#line " << line_number << " \""
          << file << "\"\n";
    } else {
      out << line << '\n';
    }
  }
  return out.str();
}

ClRuntime::ClRuntime(const std::string& spec, const std::string& binary_cache_dir)
    : binaries_(binary_cache_dir) {
  auto platforms = platformsOrEmpty();
  if (platforms.empty()) throw RenderError(missingDeviceMessage(0));
  auto devices = listDevices();
  if (devices.empty()) throw RenderError(missingDeviceMessage(platforms.size()));
  const DeviceInfo* chosen = nullptr;
  if (spec.empty()) {
    chosen = &devices.front();
  } else {
    // At most 9 digits, so stoi cannot overflow: a huge index is just an unknown device.
    static const std::regex index_form(R"(^(\d{1,9}):(\d{1,9})$)");
    static const std::regex overall_form(R"(^\d{1,9}$)");  // N: the Nth device of the table
    std::smatch m;
    if (std::regex_match(spec, m, index_form)) {
      int p = std::stoi(m[1]), d = std::stoi(m[2]);
      for (const auto& info : devices)
        if (info.platform_index == p && info.device_index == d) chosen = &info;
    } else if (std::regex_match(spec, overall_form)) {
      size_t n = std::stoul(spec);
      if (n < devices.size()) chosen = &devices[n];
    } else {
      for (const auto& info : devices)
        if (!chosen && lower(info.name).find(lower(spec)) != std::string::npos) chosen = &info;
    }
  }
  if (!chosen) {
    std::string names;
    for (const auto& info : devices)
      names += (names.empty() ? "" : ", ") + std::to_string(info.platform_index) + ":" +
               std::to_string(info.device_index) + " " + info.name;
    throw UsageError("unknown device '" + spec + "' (available: " + names + ")");
  }
  info_ = *chosen;
  // GRIDRT_MAX_BUFFER_BYTES: behave as a device whose largest buffer is at most this (a
  // rehearsal of a smaller device, and how the tests reach the out-of-resources exit).
  if (const char* limit = std::getenv("GRIDRT_MAX_BUFFER_BYTES"); limit && *limit) {
    static const std::regex digits(R"(^\d{1,19}$)");
    if (!std::regex_match(limit, digits) || std::stoull(limit) == 0)
      throw RenderError(std::string("GRIDRT_MAX_BUFFER_BYTES: expected a positive number of "
                                    "bytes, got '") +
                        limit + "'");
    info_.max_alloc_bytes = std::min(info_.max_alloc_bytes, std::stoull(limit));
  }
  std::vector<cl::Device> platform_devices;
  platforms[info_.platform_index].getDevices(CL_DEVICE_TYPE_ALL, &platform_devices);
  device_ = platform_devices[info_.device_index];
  device_identity_ = platforms[info_.platform_index].getInfo<CL_PLATFORM_VERSION>() + "\n" +
                     info_.name + "\n" + device_.getInfo<CL_DEVICE_VERSION>() + "\n" +
                     device_.getInfo<CL_DRIVER_VERSION>();
  try {
    context_ = cl::Context(device_);
    // Profiling: the PE kernels' own time on the device (eventMs), apart from transfers.
    queue_ = cl::CommandQueue(context_, device_, CL_QUEUE_PROFILING_ENABLE);
  } catch (const cl::Error& e) {
    throw RenderError("cannot create an OpenCL context on '" + info_.name +
                      "': " + clErrorName(e.err()) +
                      " (with PoCL, check that $POCL_CACHE_DIR or ~/.cache is writable)");
  }
}

// Standard error sent to /dev/null while it lives. PoCL's compiler prints its diagnostics
// ("3 errors generated.") straight to the process's stderr; the build log holds the same
// words, and gridrt reports them in its own one-line message.
namespace {
class SilencedStderr {
 public:
  SilencedStderr() {
    std::fflush(stderr);
    saved_ = ::dup(2);
    const int null = ::open("/dev/null", O_WRONLY);
    if (saved_ >= 0 && null >= 0) ::dup2(null, 2);
    if (null >= 0) ::close(null);
  }
  ~SilencedStderr() {
    std::fflush(stderr);
    if (saved_ >= 0) ::dup2(saved_, 2), ::close(saved_);
  }
  SilencedStderr(const SilencedStderr&) = delete;
  SilencedStderr& operator=(const SilencedStderr&) = delete;

 private:
  int saved_ = -1;
};
}  // namespace

cl::Program& ClRuntime::program(const std::string& file, const std::string& defines) {
  std::string key = file + "|" + defines;
  auto found = programs_.find(key);
  if (found != programs_.end()) return found->second;
  const std::string source = assembleKernelSource(file);
  // OpenCL C 1.2 for portability; exact division so scalar and vector code round alike.
  std::string options = "-cl-std=CL1.2 " + defines;
  // GRIDRT_KERNEL_OPTIONS: more options for the OpenCL C compiler (experiments; the tests
  // use it to reach the kernel-build-failure exit). Part of the binary cache's key.
  if (const char* extra = std::getenv("GRIDRT_KERNEL_OPTIONS"); extra && *extra)
    options += std::string(" ") + extra;
  if (info_.correctly_rounded_div_sqrt) options += " -cl-fp32-correctly-rounded-divide-sqrt";
  // The kernels' software prefetches are for a CPU device's caches (pe_closest16.h).
  if (info_.isCpu()) options += " -DGR_CPU_DEVICE";
  const std::vector<cl::Device> devices{device_};
  const std::string cache_key = device_identity_ + "\n" + options + "\n" + source;
  if (std::optional<std::vector<unsigned char>> binary = binaries_.load(cache_key)) {
    try {
      cl::Program loaded(context_, devices, cl::Program::Binaries{*binary});
      {
        SilencedStderr quiet;
        loaded.build(devices, options.c_str());
      }
      ++programs_loaded_;
      return programs_.emplace(key, loaded).first->second;
    } catch (const cl::Error&) {
      // A binary the driver refuses (one that passed the checks): compiled from source
      // below, and replaced.
    }
  }
  cl::Program program(context_, source);
  try {
    SilencedStderr quiet;
    program.build(devices, options.c_str());
  } catch (const cl::Error& e) {
    std::string log;
    try {
      log = program.getBuildInfo<CL_PROGRAM_BUILD_LOG>(device_);
    } catch (const cl::Error&) {
    }
    throw RenderError("building kernel '" + file + "' failed (" + clErrorName(e.err()) +
                      "): " + oneLine(log));
  }
  ++programs_compiled_;
  try {
    const std::vector<std::vector<unsigned char>> binaries = program.getInfo<CL_PROGRAM_BINARIES>();
    if (binaries.size() == 1) binaries_.store(cache_key, binaries[0]);
  } catch (const cl::Error&) {
    // A driver without program binaries: nothing to keep.
  }
  return programs_.emplace(key, program).first->second;
}

double eventMs(const cl::Event& event) {
  if (!event()) return 0.0;
  try {
    const cl_ulong start = event.getProfilingInfo<CL_PROFILING_COMMAND_START>();
    const cl_ulong end = event.getProfilingInfo<CL_PROFILING_COMMAND_END>();
    return end > start ? double(end - start) * 1e-6 : 0.0;
  } catch (const cl::Error&) {
    return 0.0;  // no profile for this command
  }
}

void ClRuntime::runAndWait(const std::function<void()>& enqueue) {
  cl::Event marker;
  try {
    enqueue();
    queue_.enqueueMarkerWithWaitList(nullptr, &marker);
    queue_.flush();
  } catch (...) {
    try {
      queue_.finish();  // nothing queued may outlive the data it reads
    } catch (...) {
    }
    throw;
  }
  marker.wait();  // throws if a command failed
}

namespace {
// "9708 MiB", "45 KiB", "4096 bytes": sizes in messages, never rounded to 0.
std::string sizeText(unsigned long long bytes) {
  if (bytes >= (1ull << 20)) return std::to_string(bytes >> 20) + " MiB";
  if (bytes >= (1ull << 10)) return std::to_string(bytes >> 10) + " KiB";
  return std::to_string(bytes) + " bytes";
}
}  // namespace

void ClRuntime::checkAllocation(size_t bytes, const std::string& what) const {
  if (bytes > info_.max_alloc_bytes)
    throw RenderError(what + " needs " + sizeText(bytes) + " in one buffer, " +
                      "more than the device allows (" + sizeText(info_.max_alloc_bytes) + ")");
}

std::string clErrorName(int code) {
  switch (code) {
    case CL_DEVICE_NOT_FOUND:
      return "CL_DEVICE_NOT_FOUND";
    case CL_DEVICE_NOT_AVAILABLE:
      return "CL_DEVICE_NOT_AVAILABLE";
    case CL_COMPILER_NOT_AVAILABLE:
      return "CL_COMPILER_NOT_AVAILABLE";
    case CL_MEM_OBJECT_ALLOCATION_FAILURE:
      return "CL_MEM_OBJECT_ALLOCATION_FAILURE";
    case CL_OUT_OF_RESOURCES:
      return "CL_OUT_OF_RESOURCES";
    case CL_OUT_OF_HOST_MEMORY:
      return "CL_OUT_OF_HOST_MEMORY";
    case CL_BUILD_PROGRAM_FAILURE:
      return "CL_BUILD_PROGRAM_FAILURE";
    case CL_INVALID_VALUE:
      return "CL_INVALID_VALUE";
    case CL_INVALID_BUFFER_SIZE:
      return "CL_INVALID_BUFFER_SIZE";
    case CL_INVALID_KERNEL_ARGS:
      return "CL_INVALID_KERNEL_ARGS";
    case CL_INVALID_WORK_GROUP_SIZE:
      return "CL_INVALID_WORK_GROUP_SIZE";
    case CL_INVALID_WORK_ITEM_SIZE:
      return "CL_INVALID_WORK_ITEM_SIZE";
    case CL_INVALID_GLOBAL_WORK_SIZE:
      return "CL_INVALID_GLOBAL_WORK_SIZE";
    case CL_INVALID_BUILD_OPTIONS:
      return "CL_INVALID_BUILD_OPTIONS";
    case -1001:
      return "CL_PLATFORM_NOT_FOUND_KHR";
    default:
      return "OpenCL error " + std::to_string(code);
  }
}

}  // namespace gridrt
