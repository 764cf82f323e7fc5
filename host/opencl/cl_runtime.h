// The OpenCL runtime: one object owning the chosen device, its context, its in-order
// queue and the programs built for it (RAII through opencl.hpp's reference counting).
#pragma once
#include <CL/opencl.hpp>
#include <algorithm>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "program_binary_cache.h"

namespace gridrt {

struct DeviceInfo {
  int platform_index = 0;
  int device_index = 0;
  std::string platform_name;
  std::string name;
  std::string type;  // "CPU", "GPU", "accelerator", ...
  unsigned compute_units = 0;
  size_t max_work_group_size = 0;
  unsigned long long local_mem_bytes = 0;
  unsigned long long global_mem_bytes = 0;
  unsigned long long max_alloc_bytes = 0;
  bool correctly_rounded_div_sqrt = false;
  bool isCpu() const { return type == "CPU"; }
};

// Every device of every platform, in platform:device order. Empty if no platform exists.
std::vector<DeviceInfo> listDevices();

// A table of the devices for `gridrt --list-devices`.
std::string formatDeviceTable(const std::vector<DeviceInfo>& devices);

// The kernel source of `file` (e.g. "gridrt_lists.cl") with its `#include "x.h"` lines
// replaced by the embedded headers from kernels/common, so no file is read at run time.
std::string assembleKernelSource(const std::string& file);

class ClRuntime {
 public:
  // spec: "" picks the first device of any type; "P:D" by index; "N" the Nth device of
  // --list-devices; else a case-insensitive
  // substring of the device name. Throws UsageError for an unknown device, RenderError
  // when no OpenCL platform is installed. Built programs are kept in binary_cache_dir
  // ("" for none; program_binary_cache.h).
  explicit ClRuntime(const std::string& spec,
                     const std::string& binary_cache_dir = ProgramBinaryCache::defaultDir());

  const DeviceInfo& info() const { return info_; }
  cl::Context& context() { return context_; }
  cl::CommandQueue& queue() { return queue_; }

  // Builds (once per file and options) the program of a kernel file, from the binary
  // cache when an earlier run left it there. Prints nothing; a build failure throws
  // RenderError carrying the device's build log.
  cl::Program& program(const std::string& file, const std::string& defines = "");
  // Programs this runtime loaded from the binary cache, and compiled from source.
  int programsLoaded() const { return programs_loaded_; }
  int programsCompiled() const { return programs_compiled_; }

  // Throws RenderError naming `what` if a buffer of `bytes` exceeds the device's limits.
  void checkAllocation(size_t bytes, const std::string& what) const;
  // The bytes of the device buffers made through DeviceBuffer (a buffer that grows
  // replaces its old one), and the most they ever were at once.
  void noteBufferResize(size_t old_bytes, size_t new_bytes) {
    buffer_bytes_ += new_bytes - old_bytes;
    peak_buffer_bytes_ = std::max(peak_buffer_bytes_, buffer_bytes_);
  }
  size_t peakBufferBytes() const { return peak_buffer_bytes_; }

  // Calls `enqueue` (OpenCL commands; a blocking one is fine) and waits for everything it
  // queued. Every device interaction of the intersectors goes through here. The host's
  // idle threads are TBB's, which sleep while the device's threads run (parallel_loops.h),
  // so nothing needs putting to sleep first. An exception from `enqueue` is rethrown once
  // the queue has finished.
  void runAndWait(const std::function<void()>& enqueue);

 private:
  DeviceInfo info_;
  cl::Device device_;
  cl::Context context_;
  cl::CommandQueue queue_;
  std::map<std::string, cl::Program> programs_;
  ProgramBinaryCache binaries_;
  std::string device_identity_;  // platform, device and driver versions: part of a cache key
  int programs_loaded_ = 0, programs_compiled_ = 0;
  size_t buffer_bytes_ = 0, peak_buffer_bytes_ = 0;
};

// A one-line description of an OpenCL error code (e.g. "CL_OUT_OF_RESOURCES").
std::string clErrorName(int code);

// A finished command's own run time on the device (its profiling start to end), in ms; 0 for
// an event that holds no command or no profile.
double eventMs(const cl::Event& event);

}  // namespace gridrt
