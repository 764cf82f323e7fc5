#include "gridrt_intersector.h"

#include <omp.h>

#include <algorithm>
#include <climits>
#include <cmath>

#include "prepared_triangles.h"
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
  checkTriangleLayout(grid.pe_triangles, kernel_options);
  pe_tri_begin_.uploadNow(rt_, grid.pe_tri_begin);
  pe_triangles_.uploadNow(rt_, grid.pe_triangles);
  rays_per_pe_.assign(grid.peCount(), 0);
  tests_per_pe_.assign(grid.peCount(), 0);
}

void GridRtIntersector::runPes(const std::vector<GrRay>& rays,
                               const std::vector<EntrySegment>& entries, size_t entry_count,
                               const std::vector<GrPeTask>& tasks, size_t slots, HitMode mode) {
  slot_hits_ = nullptr;
  if (tasks.empty()) return;
  const size_t n = rays.size();
  rays_.upload(rt_, rays);
  entries_.reserve(rt_, entry_count);
  for (const EntrySegment& segment : entries)
    entries_.uploadAt(rt_, segment.offset, segment.data, segment.count);
  tasks_.upload(rt_, tasks);
  slot_hits_dev_.reserve(rt_, slots);
  first_hit_key_.reserve(rt_, n);
  if (interrupt_)
    rt_.queue().enqueueFillBuffer(first_hit_key_.get(), int(INT_MAX), 0, n * sizeof(int));
  kernel_.setArg(0, tasks_.get());
  kernel_.setArg(1, entries_.get());
  kernel_.setArg(2, rays_.get());
  kernel_.setArg(3, pe_tri_begin_.get());
  kernel_.setArg(4, pe_triangles_.get());
  kernel_.setArg(5, slot_hits_dev_.get());
  kernel_.setArg(6, first_hit_key_.get());
  kernel_.setArg(7, mode == HitMode::AnyHit ? 1 : 0);
  kernel_.setArg(8, interrupt_ ? 1 : 0);
  rt_.queue().enqueueNDRangeKernel(kernel_, cl::NullRange,
                                   cl::NDRange(tasks.size() * kPeLocalSize),
                                   cl::NDRange(kPeLocalSize));
  slot_hits_ = static_cast<const GrHit*>(rt_.queue().enqueueMapBuffer(
      slot_hits_dev_.get(), CL_TRUE, CL_MAP_READ, 0, slots * sizeof(GrHit)));
}

void GridRtIntersector::releaseSlotHits() {
  if (!slot_hits_) return;
  rt_.queue().enqueueUnmapMemObject(slot_hits_dev_.get(), const_cast<GrHit*>(slot_hits_));
  slot_hits_ = nullptr;
}

void GridRtIntersector::finishBatch(const std::vector<int>& pairs_per_pe, size_t rays,
                                    uint64_t tests, size_t pairs, uint64_t skipped) {
  releaseSlotHits();
  for (int pe = 0; pe < grid_.peCount(); ++pe) {
    rays_per_pe_[pe] += pairs_per_pe[pe];
    tests_per_pe_[pe] += uint64_t(pairs_per_pe[pe]) * grid_.triangleCountOfPe(pe);
  }
  counters_.rays += rays;
  counters_.tests += tests;
  counters_.list_entries += pairs;
  counters_.skipped_pairs += skipped;
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
  runPes(rays, {{bins_.entries.data(), bins_.entries.size(), 0}}, bins_.entries.size(),
         bins_.tasks, slots, mode);
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
  max_list_length_ = std::max(max_list_length_, longest);
  finishBatch(bins_.pairs_per_pe, n, tests, slots, skipped);
  counters_.reduce_ms += clock.ms();
}

void GridRtIntersector::intersectPrimary(const PinholeView& view, const std::vector<GrRay>& rays,
                                         std::vector<GrHit>& hits, RayDiagnostics* diagnostics) {
  const size_t n = rays.size();
  hits.resize(n);
  Stopwatch clock;
  binCameraRaysByPe(grid_, view, rays.data(), n, kPeTaskRays, camera_bins_);
  counters_.lists_ms += clock.ms();

  clock.restart();
  std::vector<EntrySegment> segments;
  for (size_t t = 0; t < camera_bins_.thread_entries.size(); ++t)
    segments.push_back({camera_bins_.thread_entries[t].data(),
                        camera_bins_.thread_entries[t].size(), camera_bins_.thread_offset[t]});
  const size_t entry_count = camera_bins_.entry_count;
  runPes(rays, segments, entry_count, camera_bins_.tasks, entry_count, HitMode::Closest);
  counters_.kernel_ms += clock.ms();

  // Phase 2: a ray's list is its pairs in order of entry distance, so the first PE
  // holding a hit is the hit pair with the smallest t_enter (equal t_enter, which only
  // zero-length voxels at edges and corners share, goes to the lower PE index). Each
  // thread reduces a share of the tasks into its own per-ray best; then merged per ray.
  clock.restart();
  const auto& tasks = camera_bins_.tasks;
  const int threads = omp_get_max_threads();
  thread_best_.resize(threads);
  uint64_t tests = 0, skipped = 0;
#pragma omp parallel num_threads(threads) reduction(+ : tests, skipped)
  {
    auto& best = thread_best_[omp_get_thread_num()];
    best.assign(n, BestPair{INFINITY, INT_MAX, -1});
#pragma omp for schedule(dynamic, 64)
    for (long long k = 0; k < (long long)tasks.size(); ++k) {
      const GrPeTask& task = tasks[k];
      const int cost = grid_.triangleCountOfPe(task.pe);
      const GrPeEntry* entries = camera_bins_.entriesOf(task);
      for (int i = 0; i < task.entry_count; ++i) {
        const int s = task.first_entry + i;
        const GrHit& h = slot_hits_[s];
        if (h.prim == kSkipped) {
          ++skipped;
          continue;
        }
        tests += cost;
        const GrPeEntry& e = entries[i];
        BestPair& b = best[e.ray];
        if (h.prim >= 0 && (e.t_enter < b.t_enter || (e.t_enter == b.t_enter && task.pe < b.pe)))
          b = BestPair{e.t_enter, task.pe, s};
      }
    }
  }
  std::vector<int>* winners = diagnostics ? &diagnostics->winning_pe : nullptr;
  if (winners) winners->assign(n, -1);
#pragma omp parallel for schedule(static)
  for (long long r = 0; r < (long long)n; ++r) {
    BestPair b = thread_best_[0][r];
    for (int t = 1; t < threads; ++t) {
      const BestPair& c = thread_best_[t][r];
      if (c.t_enter < b.t_enter || (c.t_enter == b.t_enter && c.pe < b.pe)) b = c;
    }
    hits[r] = b.slot >= 0 ? slot_hits_[b.slot] : GrHit{rays[r].tmax, -1, 0.0f, 0.0f};
    if (winners) (*winners)[r] = b.slot >= 0 ? b.pe : -1;
  }
  if (!diagnostics) list_length_known_ = false;
  if (diagnostics) {
    diagnostics->tests.assign(n, 0);
    diagnostics->list_length.assign(n, 0);
    for (const GrPeTask& task : tasks)
      for (int i = 0; i < task.entry_count; ++i) {
        const int s = task.first_entry + i;
        int ray = camera_bins_.entriesOf(task)[i].ray;
        ++diagnostics->list_length[ray];
        if (slot_hits_[s].prim != kSkipped)
          diagnostics->tests[ray] += grid_.triangleCountOfPe(task.pe);
      }
    for (int length : diagnostics->list_length)
      max_list_length_ = std::max<uint64_t>(max_list_length_, length);
  }
  finishBatch(camera_bins_.pairs_per_pe, n, tests, entry_count, skipped);
  counters_.reduce_ms += clock.ms();
}

}  // namespace gridrt
