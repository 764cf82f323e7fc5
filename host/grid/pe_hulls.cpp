#include "pe_hulls.h"

#include <algorithm>

#include "outward_rounding.h"
#include "parallel_loops.h"
#include "prepared_triangles.h"

namespace gridrt {

std::vector<float> peHulls(const UniformGrid& grid) {
  std::vector<float> hulls(size_t(grid.peCount()) * 6);
  parallelFor(0, grid.peCount(), [&](int pe) {
    glm::vec3 box_lo, box_hi;
    grid.voxelBoxOfPe(pe, box_lo, box_hi);
    glm::dvec3 lo(std::numeric_limits<double>::infinity()), hi(-lo);
    for (int k = grid.pe_tri_begin[pe]; k < grid.pe_tri_begin[pe + 1]; ++k) {
      glm::dvec3 v[3];
      triangleVertices(grid.pe_triangles[k], v);
      for (const glm::dvec3& p : v) {
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
      }
    }
    float* out = &hulls[size_t(pe) * 6];
    for (int a = 0; a < 3; ++a) {
      out[a] = std::max(box_lo[a], floatBelow(lo[a] - grid.margin));
      out[3 + a] = std::min(box_hi[a], floatAbove(hi[a] + grid.margin));
    }
  });
  return hulls;
}

}  // namespace gridrt
