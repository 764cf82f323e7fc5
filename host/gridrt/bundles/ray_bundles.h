// Ray bundles: a batch's rays put in an order where rays that pierce the same voxels sit
// next to each other, so a PE receives whole runs of consecutive rays (tested 16 at a
// time from planes, kernels/gridrt_bundles.cl) instead of gathering rays one by one from
// a traversal list. Which rays each PE receives comes from the shape of the bundle (a
// voxel's footprint as seen from the rays' common origin, camera_bundles.h), a superset
// of the rays that pierce the voxel; the kernel's exact slab test, with the 3D-DDA's
// arithmetic, then keeps the pairs of the traversal lists.
#pragma once
#include <cstddef>
#include <vector>

#include "gridrt_types.h"

namespace gridrt {

// Longest task in packets: bounds a work-group's share so both cores stay busy.
constexpr int kMaxTaskPackets = 32;

struct RayBundles {
  // Bundle order -> index of the ray in the batch; -1 marks padding (never pierces).
  // Its length is a multiple of GR_PACKET_LANES.
  std::vector<int> ray_of;
  std::vector<GrBundleTask> tasks;
  size_t out_lanes = 0;  // result lanes of all tasks (each task's rounded up to a packet)
  // The tasks in runs of consecutive tasks (chunks), each run on the device on its own,
  // with results of at most max_chunk_lanes lanes: chunk c holds the tasks
  // [chunk_begin[c], chunk_begin[c + 1]) and their out_first counts from the chunk's first
  // lane. The intersector sets the limit from the device's buffer limits.
  std::vector<size_t> chunk_begin{0, 0};
  std::vector<size_t> chunk_lanes{0};
  size_t max_chunk_lanes = kMaxChunkLanes;
  size_t chunkCount() const { return chunk_lanes.size(); }
  // Lanes are indexed with int on the device (less a task's worth of room).
  static constexpr size_t kMaxChunkLanes =
      (size_t(1) << 31) - 2 * kMaxTaskPackets * GR_PACKET_LANES;

  // Queues PE `pe` for the bundle rays [first, first + count), split into tasks of at
  // most kMaxTaskPackets packets, each with its own result lanes; cull_set as in
  // GrBundleTask.
  void addRange(int pe, int first, int count, int cull_set = -1);
  void clearTasks() {
    tasks.clear();
    out_lanes = 0;
    chunk_begin.assign({0, 0});
    chunk_lanes.assign({0});
  }
};

}  // namespace gridrt
