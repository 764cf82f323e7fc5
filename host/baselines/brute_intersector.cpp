#include "brute_intersector.h"

#include "prepared_triangles.h"
#include "stopwatch.h"

namespace gridrt {

namespace {
constexpr int kLocalSize = 8;  // work-items per work-group: fixed, so PoCL compiles once
}  // namespace

BruteIntersector::BruteIntersector(ClRuntime& runtime, const std::vector<GrTriangle>& triangles,
                                   const KernelOptions& kernel_options)
    : rt_(runtime), triangle_count_(int(triangles.size())) {
  kernel_ =
      KernelCall<KernelArgs>(rt_.program("brute.cl", kernel_options.defines()), "brute_intersect");
  checkTriangleLayout(triangles, kernel_options);
  triangles_.uploadNow(rt_, triangles);
}

void BruteIntersector::intersect(const std::vector<GrRay>& rays, HitMode mode,
                                 std::vector<GrHit>& hits, RayDiagnostics* diagnostics) {
  Stopwatch clock;
  size_t n = rays.size();
  hits.resize(n);
  if (n > 0) {
    rt_.runAndWait([&] {
      rays_.upload(rt_, rays);
      hits_.reserve(rt_, n);
      KernelArgs args;
      args.rays = rays_.get();
      args.ray_count = int(n);
      args.tris = triangles_.get();
      args.tri_count = triangle_count_;
      args.any_hit = mode == HitMode::AnyHit ? 1 : 0;
      args.hits = hits_.get();
      size_t items = (n + GR_PACKET_LANES - 1) / GR_PACKET_LANES;
      size_t global = (items + kLocalSize - 1) / kLocalSize * kLocalSize;
      kernel_.enqueue(rt_.queue(), cl::NDRange(global), cl::NDRange(kLocalSize), args);
      hits_.download(rt_, hits.data(), n);
    });
  }
  counters_.rays += n;
  counters_.tests += uint64_t(n) * triangle_count_;
  counters_.tests_run += uint64_t(n) * triangle_count_;
  counters_.kernel_ms += clock.ms();
  if (diagnostics) {
    diagnostics->tests.assign(n, triangle_count_);
    diagnostics->winning_pe.assign(n, -1);
    diagnostics->list_length.assign(n, 0);
  }
}

}  // namespace gridrt
