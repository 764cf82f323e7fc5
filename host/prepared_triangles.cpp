#include "prepared_triangles.h"

namespace gridrt {

std::vector<GrTriangle> prepareTriangles(const Scene& scene) {
  std::vector<GrTriangle> out(scene.triangleCount());
  for (size_t t = 0; t < out.size(); ++t) {
    const glm::vec3& a = scene.positions[3 * t];
    glm::vec3 e1 = scene.positions[3 * t + 1] - a;
    glm::vec3 e2 = scene.positions[3 * t + 2] - a;
    out[t] = GrTriangle{a.x, a.y, a.z, e1.x, e1.y, e1.z, e2.x, e2.y, e2.z, int(t), 0, 0};
  }
  return out;
}

Bounds sceneBounds(const Scene& scene) {
  Bounds b;
  for (const auto& p : scene.positions) b.grow(p);
  return b;
}

}  // namespace gridrt
