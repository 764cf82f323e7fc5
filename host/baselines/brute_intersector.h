// Brute force on the device: every ray against every triangle (kernels/brute.cl). The
// reference every grid intersector must match exactly.
#pragma once
#include "cl_runtime.h"
#include "device_buffer.h"
#include "intersector.h"
#include "kernel_call.h"

namespace gridrt {

class BruteIntersector : public Intersector {
 public:
  BruteIntersector(ClRuntime& runtime, const std::vector<GrTriangle>& triangles,
                   const KernelOptions& kernel_options = {});
  std::string name() const override { return "brute"; }
  void intersect(const std::vector<GrRay>& rays, HitMode mode, std::vector<GrHit>& hits,
                 RayDiagnostics* diagnostics) override;

 private:
  // brute.cl's brute_intersect.
  struct KernelArgs {
    cl::Buffer rays;
    int ray_count;
    cl::Buffer tris;
    int tri_count;
    int any_hit;
    cl::Buffer hits;
    auto inOrder() const { return std::tie(rays, ray_count, tris, tri_count, any_hit, hits); }
  };

  ClRuntime& rt_;
  KernelCall<KernelArgs> kernel_;
  int triangle_count_;
  DeviceBuffer<GrTriangle> triangles_{"the triangle buffer", CL_MEM_READ_ONLY};
  DeviceBuffer<GrRay> rays_{"the ray batch", CL_MEM_READ_ONLY};
  DeviceBuffer<GrHit> hits_{"the hit buffer", CL_MEM_WRITE_ONLY};
};

}  // namespace gridrt
