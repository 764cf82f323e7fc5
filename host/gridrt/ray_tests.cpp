#include "ray_tests.h"

#include <algorithm>
#include <glm/glm.hpp>
#include <limits>

namespace gridrt {

int testsToWinnerInList(const UniformGrid& grid, const ListEntry* entries, int length,
                        int winning_pe) {
  int tests = 0;
  for (int e = 0; e < length; ++e) {
    tests += grid.triangleCountOfPe(entries[e].pe);
    if (entries[e].pe == winning_pe) break;
  }
  return tests;
}

double voxelEntryOf(const UniformGrid& grid, const GrRay& ray, int pe) {
  glm::vec3 lo, hi;
  grid.voxelBoxOfPe(pe, lo, hi);
  const double o[3] = {ray.ox, ray.oy, ray.oz}, d[3] = {ray.dx, ray.dy, ray.dz};
  double enter = ray.tmin;
  for (int a = 0; a < 3; ++a) {
    if (d[a] == 0.0) continue;  // parallel to the slab: it bounds nothing along the ray
    const double t0 = (double(lo[a]) - o[a]) / d[a], t1 = (double(hi[a]) - o[a]) / d[a];
    enter = std::max(enter, std::min(t0, t1));
  }
  return enter;
}

void addTestsToWinner(const UniformGrid& grid, const std::vector<GrRay>& rays,
                      const std::vector<PiercedPe>& pairs, const std::vector<int>& winning_pe,
                      std::vector<int>& tests) {
  for (const PiercedPe& pair : pairs) {
    const int winner = winning_pe[pair.ray];
    const GrRay& ray = rays[pair.ray];
    if (winner < 0 || pair.pe == winner ||
        voxelEntryOf(grid, ray, pair.pe) <= voxelEntryOf(grid, ray, winner))
      tests[pair.ray] += grid.triangleCountOfPe(pair.pe);
  }
}

}  // namespace gridrt
