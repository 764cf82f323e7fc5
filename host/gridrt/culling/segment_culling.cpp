#include "segment_culling.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <glm/glm.hpp>
#include <string>

#include "outward_rounding.h"
#include "parallel_loops.h"
#include "prepared_triangles.h"

namespace gridrt {

void writeSegmentCullPlanes(const GrTriangle* triangles, size_t n, float* planes) {
  const size_t stride = n + kSegmentCullPlanePadding;
  for (int p = 0; p < GR_SEG_PLANES; ++p)
    std::fill(planes + p * stride + n, planes + (p + 1) * stride, 0.0f);
  // Slices of the triangles on every core (one core took 91 ms for the 1.56M PE triangles
  // of the row of 16 bunnies).
  parallelSlices(parallelSliceCount(), [&](int me, int slices) {
    const auto [first, last] = sliceRange(n, me, slices);
    for (size_t i = first; i < last; ++i) {
      glm::dvec3 v[3];
      triangleVertices(triangles[i], v);
      const glm::dvec3 &v0 = v[0], &v1 = v[1], &v2 = v[2];
      const glm::dvec3 e1 = v1 - v0, e2 = v2 - v0, normal = glm::cross(e1, e2);
      const double scale = glm::length(e1) * glm::length(e2);
      const double reach =
          std::abs(v0.x) + std::abs(v0.y) + std::abs(v0.z) + glm::length(e1) + glm::length(e2);
      const double values[GR_SEG_PLANES] = {
          v0.x,
          v0.y,
          v0.z,
          v1.x,
          v1.y,
          v1.z,
          v2.x,
          v2.y,
          v2.z,
          normal.x,
          normal.y,
          normal.z,
          glm::length(normal) > 0.0 ? double(floatAbove(scale)) : INFINITY,
          double(floatAbove(reach))};
      for (int p = 0; p < GR_SEG_PLANES; ++p) planes[p * stride + i] = float(values[p]);
    }
  });
}

void computeSegmentCullPlanes(const std::vector<GrTriangle>& triangles,
                              std::vector<float>& planes) {
  planes.resize(GR_SEG_PLANES * (triangles.size() + kSegmentCullPlanePadding));
  writeSegmentCullPlanes(triangles.data(), triangles.size(), planes.data());
}

double segmentCullMargin(const std::vector<float>& planes, size_t index, const GrRay& ray,
                         float t_hi, double error_factor) {
  const size_t stride = planes.size() / GR_SEG_PLANES;
  auto plane = [&](int p) { return double(planes[p * stride + index]); };
  const double facing =
      std::abs(plane(GR_SEG_NX) * ray.dx + plane(GR_SEG_NY) * ray.dy + plane(GR_SEG_NZ) * ray.dz);
  const double scale = plane(GR_SEG_SCALE);
  if (!(facing * kSegmentCullMaxConditioning >= scale)) return INFINITY;
  const double reach = std::abs(ray.ox) + std::abs(ray.oy) + std::abs(ray.oz) + std::abs(t_hi);
  return error_factor * 0x1p-24 * scale / facing * (reach + plane(GR_SEG_REACH));
}

std::string segmentCullDefines() {
  char text[200];
  std::snprintf(text, sizeof text,
                "-DGR_SEG_ERROR=%.9ef -DGR_SEG_MAX_CONDITIONING=%.1ff -DGR_SEG_MIN_TRIANGLES=%d",
                kSegmentCullErrorFactor * 0x1p-24, kSegmentCullMaxConditioning,
                kSegmentCullMinTriangles);
  return text;
}

}  // namespace gridrt
