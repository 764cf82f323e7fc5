#include "gridrt_intersector.h"

#include <climits>

#include "stopwatch.h"

namespace gridrt {

namespace {
constexpr int kSkipped = -2;  // prim of a slot the interrupt skipped (kernels/gridrt_pe.cl)
}

GridRtIntersector::GridRtIntersector(ClRuntime& runtime, const UniformGrid& grid, bool interrupt,
                                     const KernelOptions& kernel_options)
    : rt_(runtime), grid_(grid), interrupt_(interrupt) {
  kernel_ = cl::Kernel(rt_.program("gridrt_pe.cl", "-DGR_PE_LOCAL_SIZE=" +
                                                        std::to_string(kPeLocalSize) + " " +
                                                        kernel_options.defines()),
                       "gridrt_pe");
  pe_tri_begin_.upload(rt_, grid.pe_tri_begin);
  pe_triangles_.upload(rt_, grid.pe_triangles);
  rays_per_pe_.assign(grid.peCount(), 0);
  tests_per_pe_.assign(grid.peCount(), 0);
}

void GridRtIntersector::intersect(const std::vector<GrRay>& rays, HitMode mode,
                                  std::vector<GrHit>& hits, RayDiagnostics* diagnostics) {
  const size_t n = rays.size();
  hits.resize(n);
  Stopwatch clock;
  computeTraversalLists(grid_, rays.data(), n, lists_);
  binByPe(lists_, grid_.peCount(), kPeTaskRays, bins_);
  counters_.lists_ms += clock.ms();

  clock.restart();
  const size_t slots = lists_.entries.size();
  slot_hits_.resize(slots);
  if (!bins_.tasks.empty()) {
    rays_.upload(rt_, rays);
    entries_.upload(rt_, bins_.entries);
    tasks_.upload(rt_, bins_.tasks);
    slot_hits_dev_.reserve(rt_, slots);
    first_hit_slot_.reserve(rt_, n);
    if (interrupt_)
      rt_.queue().enqueueFillBuffer(first_hit_slot_.get(), int(INT_MAX), 0, n * sizeof(int));
    kernel_.setArg(0, tasks_.get());
    kernel_.setArg(1, entries_.get());
    kernel_.setArg(2, rays_.get());
    kernel_.setArg(3, pe_tri_begin_.get());
    kernel_.setArg(4, pe_triangles_.get());
    kernel_.setArg(5, slot_hits_dev_.get());
    kernel_.setArg(6, first_hit_slot_.get());
    kernel_.setArg(7, mode == HitMode::AnyHit ? 1 : 0);
    kernel_.setArg(8, interrupt_ ? 1 : 0);
    rt_.queue().enqueueNDRangeKernel(kernel_, cl::NullRange,
                                     cl::NDRange(bins_.tasks.size() * kPeLocalSize),
                                     cl::NDRange(kPeLocalSize));
    slot_hits_dev_.download(rt_, slot_hits_.data(), slots);
  }
  counters_.kernel_ms += clock.ms();

  // Phase 2: walk each ray's list nearest first; the first PE holding a hit wins.
  clock.restart();
  if (diagnostics) {
    diagnostics->tests.assign(n, 0);
    diagnostics->winning_pe.assign(n, -1);
    diagnostics->list_length.assign(n, 0);
  }
  uint64_t tests = 0, skipped = 0, longest = 0;
#pragma omp parallel for schedule(static) reduction(+ : tests, skipped) reduction(max : longest)
  for (long long r = 0; r < (long long)n; ++r) {
    GrHit best{rays[r].tmax, -1, 0.0f, 0.0f};
    int winner = -1, ray_tests = 0;
    for (int s = lists_.begin[r]; s < lists_.begin[r + 1]; ++s) {
      const GrHit& h = slot_hits_[s];
      int pe = lists_.entries[s].pe;
      if (h.prim == kSkipped) {
        ++skipped;
        continue;
      }
      ray_tests += grid_.triangleCountOfPe(pe);
      if (winner < 0 && h.prim >= 0) {
        best = h;
        winner = pe;
      }
    }
    hits[r] = best;
    tests += ray_tests;
    longest = std::max<uint64_t>(longest, lists_.lengthOf(r));
    if (diagnostics) {
      diagnostics->tests[r] = ray_tests;
      diagnostics->winning_pe[r] = winner;
      diagnostics->list_length[r] = lists_.lengthOf(r);
    }
  }
  for (int pe = 0; pe < grid_.peCount(); ++pe) {
    rays_per_pe_[pe] += bins_.pairs_per_pe[pe];
    tests_per_pe_[pe] += uint64_t(bins_.pairs_per_pe[pe]) * grid_.triangleCountOfPe(pe);
  }
  counters_.rays += n;
  counters_.tests += tests;
  counters_.list_entries += slots;
  counters_.skipped_pairs += skipped;
  max_list_length_ = std::max(max_list_length_, longest);
  counters_.reduce_ms += clock.ms();
}

}  // namespace gridrt
