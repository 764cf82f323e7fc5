#include "dda_intersector.h"

#include "grid_dda.h"
#include "prepared_triangles.h"
#include "stopwatch.h"

namespace gridrt {

namespace {
constexpr int kLocalSize = 64;  // work-items per work-group: fixed, so PoCL compiles once
}

DdaIntersector::DdaIntersector(ClRuntime& runtime, const UniformGrid& grid,
                               const KernelOptions& kernel_options)
    : rt_(runtime), grid_(grid) {
  kernel_ =
      KernelCall<KernelArgs>(rt_.program("dda.cl", kernel_options.defines()), "dda_intersect");
  checkTriangleLayout(grid.pe_triangles, kernel_options);
  pe_of_voxel_.uploadNow(rt_, grid.pe_of_voxel);
  pe_tri_begin_.uploadNow(rt_, grid.pe_tri_begin);
  pe_triangles_.uploadNow(rt_, grid.pe_triangles);
}

void DdaIntersector::intersect(const std::vector<GrRay>& rays, HitMode mode,
                               std::vector<GrHit>& hits, RayDiagnostics* diagnostics) {
  Stopwatch clock;
  size_t n = rays.size();
  hits.resize(n);
  tests_host_.resize(n);
  if (n > 0) {
    rt_.runAndWait([&] {
      rays_.upload(rt_, rays);
      hits_.reserve(rt_, n);
      tests_.reserve(rt_, n);
      KernelArgs args;
      args.rays = rays_.get();
      args.ray_count = int(n);
      args.grid = grid_.info;
      args.pe_of_voxel = pe_of_voxel_.get();
      args.pe_tri_begin = pe_tri_begin_.get();
      args.pe_tris = pe_triangles_.get();
      args.any_hit = mode == HitMode::AnyHit ? 1 : 0;
      args.hits = hits_.get();
      args.tests = tests_.get();
      size_t global = (n + kLocalSize - 1) / kLocalSize * kLocalSize;
      kernel_.enqueue(rt_.queue(), cl::NDRange(global), cl::NDRange(kLocalSize), args);
      hits_.download(rt_, hits.data(), n);
      tests_.download(rt_, tests_host_.data(), n);
    });
  }
  counters_.rays += n;
  uint64_t tests = 0;
  for (int t : tests_host_) tests += uint64_t(t);
  counters_.tests += tests;
  counters_.tests_run += tests;
  counters_.kernel_ms += clock.ms();
  if (diagnostics) {
    diagnostics->tests = tests_host_;
    diagnostics->winning_pe.assign(n, -1);
    diagnostics->list_length.assign(n, 0);
    // The winning PE is the voxel holding the hit point; recovered on the host by
    // walking the same DDA to the hit distance.
    for (size_t r = 0; r < n; ++r) {
      if (hits[r].prim < 0) continue;
      GrDda s;
      const GrRay& ray = rays[r];
      const GrGridInfo& g = grid_.info;
      if (!gr_dda_begin(&g, ray.ox, ray.oy, ray.oz, ray.dx, ray.dy, ray.dz, ray.tmin, ray.tmax, &s))
        continue;
      int length = 0;
      do {
        int pe = grid_.pe_of_voxel[s.ix + g.nx * (s.iy + g.ny * s.iz)];
        if (pe < 0) continue;
        ++length;
        if (diagnostics->winning_pe[r] < 0 && hits[r].t >= s.t_enter && hits[r].t <= s.t_exit)
          diagnostics->winning_pe[r] = pe;
      } while (gr_dda_step(&g, &s));
      diagnostics->list_length[r] = length;
    }
  }
}

}  // namespace gridrt
