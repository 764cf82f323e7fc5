#include "reference_intersector.h"

#include "parallel_loops.h"
#include "prepared_triangles.h"
#include "stopwatch.h"

namespace gridrt {

bool intersectTriangleDouble(const glm::dvec3& o, const glm::dvec3& d, const glm::dvec3& v0,
                             const glm::dvec3& e1, const glm::dvec3& e2, double& t, double& u,
                             double& v) {
  glm::dvec3 p = glm::cross(d, e2);
  double det = glm::dot(e1, p);
  if (det == 0.0) return false;
  double inv = 1.0 / det;
  glm::dvec3 s = o - v0;
  u = glm::dot(s, p) * inv;
  glm::dvec3 q = glm::cross(s, e1);
  v = glm::dot(d, q) * inv;
  t = glm::dot(e2, q) * inv;
  return u >= 0.0 && v >= 0.0 && u + v <= 1.0;
}

ReferenceIntersector::ReferenceIntersector(const Scene& scene) {
  size_t n = scene.triangleCount();
  v0_.resize(n);
  e1_.resize(n);
  e2_.resize(n);
  for (size_t t = 0; t < n; ++t) {
    glm::vec3 v[3];
    canonicalVertices(&scene.positions[3 * t], v);  // exact ties stay exact (duplicates)
    glm::dvec3 a(v[0]), b(v[1]), c(v[2]);
    v0_[t] = a;
    e1_[t] = b - a;
    e2_[t] = c - a;
  }
}

void ReferenceIntersector::intersect(const std::vector<GrRay>& rays, HitMode mode,
                                     std::vector<GrHit>& hits, RayDiagnostics* diagnostics) {
  Stopwatch clock;
  const long long n = (long long)rays.size();
  const size_t tris = v0_.size();
  hits.resize(rays.size());
  parallelForDynamic(0LL, (long long)(n), 64LL, [&](long long r) {
    const GrRay& ray = rays[r];
    glm::dvec3 o(ray.ox, ray.oy, ray.oz), d(ray.dx, ray.dy, ray.dz);
    double best = ray.tmax;
    GrHit hit{ray.tmax, -1, 0.0f, 0.0f};
    for (size_t t = 0; t < tris; ++t) {
      double tt, u, v;
      if (intersectTriangleDouble(o, d, v0_[t], e1_[t], e2_[t], tt, u, v) && tt > ray.tmin &&
          tt < best) {
        best = tt;
        hit = GrHit{float(tt), int(t), float(u), float(v)};
        if (mode == HitMode::AnyHit) break;
      }
    }
    hits[r] = hit;
  });
  counters_.rays += rays.size();
  counters_.tests += uint64_t(rays.size()) * tris;
  counters_.tests_run += uint64_t(rays.size()) * tris;
  counters_.kernel_ms += clock.ms();
  if (diagnostics) {
    diagnostics->tests.assign(rays.size(), int(tris));
    diagnostics->winning_pe.assign(rays.size(), -1);
    diagnostics->list_length.assign(rays.size(), 0);
  }
}

}  // namespace gridrt
