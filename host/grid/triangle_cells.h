// The cells of a grid that one triangle overlaps: the binning step both grids share (the
// uniform grid's voxels, each adaptive node's cells). A cell is listed when the triangle
// overlaps it grown by the grid's margin m, decided exactly (triangle_box_overlap.h).
#pragma once
#include <glm/glm.hpp>
#include <vector>

#include "triangle_box_overlap.h"
#include "uniform_grid.h"

namespace gridrt {

// Calls emit(x, y, z) for every cell of the grid whose planes per axis are `planes`
// (`axis` their AxisCells, with the same margin m) that the triangle v overlaps, grown by
// m, in x-fastest order. The triangle overlaps the grid grown by m (else it would not be
// binned there). Two cases need no separating-axis test:
// - its bounding box meets one grown cell only: it lies inside it, since the grown cells
//   cover the grown grid;
// - its bounding box meets several cells along one axis only and lies inside the cell's
//   grown extent on the other two: the triangle then meets a cell exactly where its own
//   extent along that axis meets the cell's (the triangle is connected, so its points'
//   coordinates along the axis fill that extent). Most triangles that cross a cell face
//   cross one: 70 % of those binned on the scattered copies, 87 % on the row (uneven
//   scenes, tools/make_uneven_scenes).
// The comparisons are those of the test's bounding-box step, in the same double values.
template <typename Emit>
void forEachCellOfTriangle(const glm::dvec3 (&v)[3], const AxisCells (&axis)[3],
                           const std::vector<float> (&planes)[3], double m, Emit&& emit) {
  const glm::dvec3 tlo = glm::min(v[0], glm::min(v[1], v[2]));
  const glm::dvec3 thi = glm::max(v[0], glm::max(v[1], v[2]));
  int first[3], last[3];
  for (int a = 0; a < 3; ++a) axis[a].range(tlo[a], thi[a], first[a], last[a]);
  int spanning = -1, spans = 0;
  for (int a = 0; a < 3; ++a)
    if (first[a] != last[a]) ++spans, spanning = a;
  if (spans == 0) {
    emit(first[0], first[1], first[2]);
    return;
  }
  auto cellLo = [&](int a, int k) { return double(planes[a][k]) - m; };
  auto cellHi = [&](int a, int k) { return double(planes[a][k + 1]) + m; };
  if (spans == 1) {
    bool inside = true;
    for (int a = 0; a < 3; ++a)
      if (a != spanning)
        inside = inside && cellLo(a, first[a]) <= tlo[a] && thi[a] <= cellHi(a, first[a]);
    if (inside) {
      int c[3] = {first[0], first[1], first[2]};
      const int s = spanning;
      for (c[s] = first[s]; c[s] <= last[s]; ++c[s])
        if (cellLo(s, c[s]) <= thi[s] && tlo[s] <= cellHi(s, c[s])) emit(c[0], c[1], c[2]);
      return;
    }
  }
  const TriangleBoxTest test(v[0], v[1], v[2]);
  for (int z = first[2]; z <= last[2]; ++z)
    for (int y = first[1]; y <= last[1]; ++y)
      for (int x = first[0]; x <= last[0]; ++x) {
        const glm::dvec3 lo(cellLo(0, x), cellLo(1, y), cellLo(2, z));
        const glm::dvec3 hi(cellHi(0, x), cellHi(1, y), cellHi(2, z));
        if (test.overlaps(lo, hi)) emit(x, y, z);
      }
}

}  // namespace gridrt
