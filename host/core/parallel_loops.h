// The host's parallel loops, on oneTBB (Debian's libtbb-dev).
//
// TBB's idle threads spin briefly, yielding, and then sleep, so between two loops they leave
// the cores to PoCL's threads running the kernels and to the machine's other processes
// (GCC's OpenMP runtime polled for 300,000 rounds after every region; docs/performance.md,
// "Sharing the machine"). The thread count is TBB's: every core, or what --threads sets
// through a tbb::global_control (host/app/thread_count.h).
//
// Every loop here splits its range statically into contiguous parts, one per slice, so a
// loop's partition depends only on the range and the slice count, never on timing.
#pragma once
#include <tbb/blocked_range.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>
#include <tbb/partitioner.h>
#include <tbb/task_arena.h>

#include <cstddef>
#include <utility>

namespace gridrt {

// How many slices a loop is cut into: the threads the host may use (every core, or the
// limit a tbb::global_control sets, which may exceed the cores).
inline int parallelSliceCount() {
  return int(tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism));
}

// Scratch that belongs to the running thread rather than to a slice: threadSlotCount()
// slots, the caller's being currentThreadSlot(). Only for loop bodies that start no
// parallel loop of their own (a thread waiting on one may run another body meanwhile).
inline int threadSlotCount() { return tbb::this_task_arena::max_concurrency(); }
inline int currentThreadSlot() { return tbb::this_task_arena::current_thread_index(); }

// body(slice, count) for every slice in [0, count), in parallel; count is usually
// parallelSliceCount(), read once by the caller to size the slices' scratch, which is
// indexed by `slice` (a thread may run several slices).
template <typename Body>
void parallelSlices(int count, const Body& body) {
  if (count <= 1) return body(0, 1);
  tbb::parallel_for(
      0, count, [&](int slice) { body(slice, count); }, tbb::static_partitioner());
}

// The part [first, second) of [0, n) that slice `slice` of `count` takes: consecutive
// parts, in slice order, their sizes differing by at most one.
inline std::pair<size_t, size_t> sliceRange(size_t n, int slice, int count) {
  return {n * size_t(slice) / size_t(count), n * size_t(slice + 1) / size_t(count)};
}

// body(i) for every i in [begin, end), split statically into one part per thread.
template <typename Index, typename Body>
void parallelFor(Index begin, Index end, const Body& body) {
  if (end <= begin) return;
  tbb::parallel_for(
      tbb::blocked_range<Index>(begin, end),
      [&](const tbb::blocked_range<Index>& r) {
        for (Index i = r.begin(); i != r.end(); ++i) body(i);
      },
      tbb::static_partitioner());
}

// body(i) for every i in [begin, end), handed out in parts of `grain` to whichever thread
// is free: for loops whose iterations differ widely in cost.
template <typename Index, typename Body>
void parallelForDynamic(Index begin, Index end, Index grain, const Body& body) {
  if (end <= begin) return;
  tbb::parallel_for(
      tbb::blocked_range<Index>(begin, end, grain),
      [&](const tbb::blocked_range<Index>& r) {
        for (Index i = r.begin(); i != r.end(); ++i) body(i);
      },
      tbb::simple_partitioner());
}

}  // namespace gridrt
