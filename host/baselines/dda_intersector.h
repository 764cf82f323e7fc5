// The classic uniform-grid traversal of the paper's Fig. 1 (kernels/dda.cl): one
// work-item per ray walks the grid on the device and stops at the first voxel with a hit.
#pragma once
#include "cl_runtime.h"
#include "device_buffer.h"
#include "intersector.h"
#include "kernel_call.h"
#include "uniform_grid.h"

namespace gridrt {

class DdaIntersector : public Intersector {
 public:
  DdaIntersector(ClRuntime& runtime, const UniformGrid& grid,
                 const KernelOptions& kernel_options = {});
  // The intersector keeps a reference to its grid: a temporary would dangle.
  DdaIntersector(ClRuntime&, UniformGrid&&, const KernelOptions& = {}) = delete;
  std::string name() const override { return "dda"; }
  void intersect(const std::vector<GrRay>& rays, HitMode mode, std::vector<GrHit>& hits,
                 RayDiagnostics* diagnostics) override;

 private:
  ClRuntime& rt_;
  const UniformGrid& grid_;
  // dda.cl's dda_intersect.
  struct KernelArgs {
    cl::Buffer rays;
    int ray_count;
    GrGridInfo grid;
    cl::Buffer pe_of_voxel, pe_tri_begin, pe_tris;
    int any_hit;
    cl::Buffer hits, tests;
    auto inOrder() const {
      return std::tie(rays, ray_count, grid, pe_of_voxel, pe_tri_begin, pe_tris, any_hit, hits,
                      tests);
    }
  };
  KernelCall<KernelArgs> kernel_;
  DeviceBuffer<int> pe_of_voxel_{"the voxel map", CL_MEM_READ_ONLY};
  DeviceBuffer<int> pe_tri_begin_{"the PE offsets", CL_MEM_READ_ONLY};
  DeviceBuffer<GrTriangle> pe_triangles_{"the PE triangles", CL_MEM_READ_ONLY};
  DeviceBuffer<GrRay> rays_{"the ray batch", CL_MEM_READ_ONLY};
  DeviceBuffer<GrHit> hits_{"the hit buffer", CL_MEM_WRITE_ONLY};
  DeviceBuffer<int> tests_{"the test counters", CL_MEM_WRITE_ONLY};
  std::vector<int> tests_host_;
};

}  // namespace gridrt
