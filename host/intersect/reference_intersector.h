// The exact reference (--accel reference): brute force on the host in double precision
// against the scene's original vertices, ties broken by the lower triangle index. Slow
// by design; it is the ground truth the float intersectors are measured against.
#pragma once
#include "intersector.h"
#include "scene.h"

namespace gridrt {

class ReferenceIntersector : public Intersector {
 public:
  explicit ReferenceIntersector(const Scene& scene);
  std::string name() const override { return "reference"; }
  void intersect(const std::vector<GrRay>& rays, HitMode mode, std::vector<GrHit>& hits,
                 RayDiagnostics* diagnostics) override;

 private:
  std::vector<glm::dvec3> v0_, e1_, e2_;
};

// Moeller-Trumbore in double: returns true with t, u, v on a hit of the closed triangle.
bool intersectTriangleDouble(const glm::dvec3& o, const glm::dvec3& d, const glm::dvec3& v0,
                             const glm::dvec3& e1, const glm::dvec3& e2, double& t, double& u,
                             double& v);

}  // namespace gridrt
