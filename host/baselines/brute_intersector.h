// Brute force on the device: every ray against every triangle (kernels/brute.cl). The
// reference every grid intersector must match exactly.
#pragma once
#include "cl_runtime.h"
#include "device_buffer.h"
#include "intersector.h"

namespace gridrt {

class BruteIntersector : public Intersector {
 public:
  BruteIntersector(ClRuntime& runtime, const std::vector<GrTriangle>& triangles,
                   const KernelOptions& kernel_options = {});
  std::string name() const override { return "brute"; }
  void intersect(const std::vector<GrRay>& rays, HitMode mode, std::vector<GrHit>& hits,
                 RayDiagnostics* diagnostics) override;

 private:
  ClRuntime& rt_;
  cl::Kernel kernel_;
  int triangle_count_;
  DeviceBuffer<GrTriangle> triangles_{"the triangle buffer", CL_MEM_READ_ONLY};
  DeviceBuffer<GrRay> rays_{"the ray batch", CL_MEM_READ_ONLY};
  DeviceBuffer<GrHit> hits_{"the hit buffer", CL_MEM_WRITE_ONLY};
};

}  // namespace gridrt
