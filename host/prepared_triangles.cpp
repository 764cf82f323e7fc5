#include "prepared_triangles.h"

#include <stdexcept>

namespace gridrt {

std::vector<GrTriangle> prepareTriangles(const Scene& scene, const KernelOptions& kernel) {
  std::vector<GrTriangle> out(scene.triangleCount());
  const bool vertices = kernel.watertight;
  for (size_t t = 0; t < out.size(); ++t) {
    const glm::vec3& a = scene.positions[3 * t];
    glm::vec3 b = scene.positions[3 * t + 1], c = scene.positions[3 * t + 2];
    if (!vertices) {
      b -= a;
      c -= a;
    }
    out[t] = GrTriangle{a.x, a.y, a.z, b.x, b.y, b.z, c.x, c.y, c.z, int(t), vertices ? 1 : 0, 0};
  }
  return out;
}

void triangleVertices(const GrTriangle& t, glm::dvec3 v[3]) {
  v[0] = glm::dvec3(t.v0x, t.v0y, t.v0z);
  glm::dvec3 b(t.e1x, t.e1y, t.e1z), c(t.e2x, t.e2y, t.e2z);
  v[1] = t.vertex_layout ? b : v[0] + b;
  v[2] = t.vertex_layout ? c : v[0] + c;
}

void checkTriangleLayout(const std::vector<GrTriangle>& triangles, const KernelOptions& kernel) {
  int want = kernel.watertight ? 1 : 0;
  for (const auto& t : triangles)
    if (t.vertex_layout != want)
      throw std::logic_error("triangles prepared for the other ray/triangle test");
}

Bounds sceneBounds(const Scene& scene) {
  Bounds b;
  for (const auto& p : scene.positions) b.grow(p);
  return b;
}

}  // namespace gridrt
