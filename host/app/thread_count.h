// --threads N: the number of threads for the host's loops and for PoCL's CPU device
// together (as pbrt's --nthreads, Mitsuba's -t and Blender's -t set one count for all).
#pragma once
#include <tbb/global_control.h>

#include <optional>

namespace gridrt {

// While it lives, the host's parallel loops use at most `threads` threads (> 0), and PoCL's
// pthread device, if it has not been initialised yet, as many but at most one a CPU: PoCL reads
// POCL_MAX_PTHREAD_COUNT when it first sets up its devices (PoCL 3.1 ignores
// POCL_CPU_MAX_CU_NUM), so make it before the first OpenCL call. 0 changes nothing: every
// core, or what POCL_MAX_PTHREAD_COUNT says for the device.
class ThreadLimit {
 public:
  explicit ThreadLimit(int threads);

 private:
  std::optional<tbb::global_control> host_limit_;
};

}  // namespace gridrt
