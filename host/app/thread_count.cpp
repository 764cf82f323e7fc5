#include "thread_count.h"

#include <sched.h>

#include <algorithm>
#include <cstdlib>
#include <string>

namespace gridrt {

namespace {
// The CPUs this process may run on (PoCL's pthread device pins one thread to each; asked
// for more threads than that, PoCL 3.1 aborts in pthread_setaffinity_np).
int usableCpus() {
  cpu_set_t set;
  CPU_ZERO(&set);
  if (sched_getaffinity(0, sizeof(set), &set) != 0) return 1;
  return std::max(1, CPU_COUNT(&set));
}
}  // namespace

ThreadLimit::ThreadLimit(int threads) {
  if (threads <= 0) return;
  host_limit_.emplace(tbb::global_control::max_allowed_parallelism, size_t(threads));
  // The variable is PoCL's own interface; --threads on the command line wins over it.
  const int device_threads = std::min(threads, usableCpus());
  setenv("POCL_MAX_PTHREAD_COUNT", std::to_string(device_threads).c_str(), /*overwrite=*/1);
}

}  // namespace gridrt
