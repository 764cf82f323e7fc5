#include "openmp_spin.h"

#include <unistd.h>

#include <cstdlib>

namespace gridrt {

void restartWithShortOpenMpSpin(char** argv) {
  if (std::getenv("GOMP_SPINCOUNT") || std::getenv("OMP_WAIT_POLICY")) return;
  if (setenv("GOMP_SPINCOUNT", kOpenMpSpinCount, /*overwrite=*/0) != 0) return;
  execv("/proc/self/exe", argv);
  // Still here: the restart failed; run with libgomp's default spin.
}

}  // namespace gridrt
