// libgomp's idle threads spin (GOMP_SPINCOUNT iterations, 300,000 by default: about a
// millisecond) after every parallel region before they sleep; on a CPU device that spin
// competes with the device's own threads. libgomp reads GOMP_SPINCOUNT only when it loads,
// before main, so the executable restarts itself once with a shorter spin.
#pragma once

namespace gridrt {

// The spin count gridrt runs with. Measured (6 alternated rounds, GOMP_SPINCOUNT set
// outside): default Whitted 640x480 105.0 -> 96.6 ms (kernels 49.4 -> 42.3, phase 2
// 8.2 -> 5.5), bunny Whitted 31.9 -> 29.9 ms, bunny 1280x960 primary and bunny_res4
// unchanged; 3,000 measured as 10,000, 30,000 in between.
constexpr const char* kOpenMpSpinCount = "10000";

// Unless the user set GOMP_SPINCOUNT or OMP_WAIT_POLICY: sets GOMP_SPINCOUNT and executes
// this program again with the same arguments (never returns then). Returns if the
// restart is not needed or not possible (the program then runs as it is).
void restartWithShortOpenMpSpin(char** argv);

}  // namespace gridrt
