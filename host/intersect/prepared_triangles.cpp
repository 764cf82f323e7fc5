#include "prepared_triangles.h"

#include <stdexcept>
#include <utility>

#include "moller_trumbore.h"

namespace gridrt {

namespace {
bool lexLess(const glm::vec3& p, const glm::vec3& q) {
  return p.x != q.x ? p.x < q.x : p.y != q.y ? p.y < q.y : p.z < q.z;
}
}  // namespace

void canonicalVertices(const glm::vec3* in, glm::vec3 out[3]) {
  out[0] = in[0];
  out[1] = in[1];
  out[2] = in[2];
  if (lexLess(out[1], out[0])) std::swap(out[0], out[1]);
  if (lexLess(out[2], out[1])) std::swap(out[1], out[2]);
  if (lexLess(out[1], out[0])) std::swap(out[0], out[1]);
}

GrTriangle prepareTriangle(const glm::vec3 v[3], int prim, const KernelOptions& kernel) {
  const bool vertices = kernel.watertight;
  const glm::vec3& a = v[0];
  glm::vec3 b = v[1], c = v[2];
  if (!vertices) {
    b -= a;
    c -= a;
  }
  GrTriangle tri{a.x, a.y,  a.z,  b.x,  b.y, b.z, c.x, c.y, c.z, prim, vertices ? 1 : 0,
                 0,   0.0f, 0.0f, 0.0f, 0};
  if (!vertices) gr_triangle_normal(b.x, b.y, b.z, c.x, c.y, c.z, &tri.nx, &tri.ny, &tri.nz);
  return tri;
}

std::vector<GrTriangle> prepareTriangles(const Scene& scene, const KernelOptions& kernel) {
  std::vector<GrTriangle> out(scene.triangleCount());
  for (size_t t = 0; t < out.size(); ++t) {
    glm::vec3 v[3];
    canonicalVertices(&scene.positions[3 * t], v);
    out[t] = prepareTriangle(v, int(t), kernel);
  }
  return out;
}

void triangleVertices(const GrTriangle& t, glm::dvec3 v[3]) {
  v[0] = glm::dvec3(t.v0x, t.v0y, t.v0z);
  glm::dvec3 b(t.e1x, t.e1y, t.e1z), c(t.e2x, t.e2y, t.e2z);
  v[1] = t.vertex_layout ? b : v[0] + b;
  v[2] = t.vertex_layout ? c : v[0] + c;
}

void checkTriangleLayout(const GrTriangle* triangles, size_t count, const KernelOptions& kernel) {
  int want = kernel.watertight ? 1 : 0;
  for (size_t i = 0; i < count; ++i)
    if (triangles[i].vertex_layout != want)
      throw std::logic_error("triangles prepared for the other ray/triangle test");
}

Bounds sceneBounds(const Scene& scene) {
  Bounds b;
  for (const auto& p : scene.positions) b.grow(p);
  return b;
}

}  // namespace gridrt
