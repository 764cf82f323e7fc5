// The GridRT intersector (Nery et al.): traversal lists on the host, one work-group per
// PE task on the device (phase 1: one in-voxel hit per ray and PE), and the phase-2
// reduction on the host (the first PE in a ray's list holding a hit wins).
#pragma once
#include <functional>

#include "camera_bundles.h"
#include "cl_runtime.h"
#include "device_buffer.h"
#include "intersector.h"
#include "kernel_call.h"
#include "light_bundles.h"
#include "light_culling.h"
#include "packet_culling.h"
#include "pe_binning.h"
#include "ray_bundles.h"
#include "traversal_lists.h"
#include "uniform_grid.h"

namespace gridrt {

// Packets per PE work-group (fixed: each new local size is a new compile on PoCL). Each
// work-item of the packet kernels tests one packet (GR_PACKET_LANES rays in float16 lanes),
// each of the lane kernels one ray (PeLayout), so one task holds up to 64 rays.
constexpr int kPeLocalSize = 4;
constexpr int kPeTaskRays = kPeLocalSize * GR_PACKET_LANES;
// Fewer shadow rays than this towards one light go through per-ray traversal lists: a
// sparse cube wastes most packet lanes. On the default scene small batches cost less as
// lists and large ones far less as bundles; with segment culling in both, the secondary
// hits' mid-sized batches are faster as bundles, and a lower threshold made no difference
// (docs/history.md).
constexpr size_t kMinLightBundleRays = 8192;
// Light bundles that would test more lanes than this per ray (a light among dense geometry
// with a fine grid: every near voxel covers a wide cone) also fall back to the lists,
// whose cost follows the real (ray, PE) pairs.
constexpr size_t kMaxLightBundleLanesPerRay = 64;
// One batch's pairs or results buffer takes at most this share of the device's global
// memory (the batch holds a few buffers of that order at once: rays, pairs, results).
constexpr unsigned long long kBatchMemoryShare = 4;

// The batches whose PEs emulate the paper's interrupt chain on the device: a PE skips a
// ray once an earlier PE of the ray's list has a hit. The hits are the same either way.
enum class PeInterrupt {
  Off,         // none: every PE tests every ray it receives
  CameraRays,  // camera bundles only (gridrt's default): faster than Off on the bunny's
               // primary and Whitted frames, the same on the default Whitted frame (its
               // walls are hit in the first PE); docs/history.md
  AllRays,     // every batch (--pe-interrupt): shadow and list batches too. Mixed, so not
               // the default: faster on some Whitted frames, slower on others, and the
               // balance changes with the machine
};

// The layout `asked` for on `device`: Auto is Packets on a CPU device, Lanes on any other.
inline PeLayout peLayoutFor(PeLayout asked, const DeviceInfo& device) {
  if (asked != PeLayout::Auto) return asked;
  return device.isCpu() ? PeLayout::Packets : PeLayout::Lanes;
}

class GridRtIntersector : public Intersector {
 public:
  GridRtIntersector(ClRuntime& runtime, const UniformGrid& grid, PeInterrupt interrupt,
                    const KernelOptions& kernel_options = {});
  // The intersector keeps a reference to its grid: a temporary would dangle.
  GridRtIntersector(ClRuntime&, UniformGrid&&, PeInterrupt, const KernelOptions& = {}) = delete;
  ~GridRtIntersector() override;
  GridRtIntersector(const GridRtIntersector&) = delete;
  GridRtIntersector& operator=(const GridRtIntersector&) = delete;
  std::string name() const override { return allInterrupt() ? "gridrt-interrupt" : "gridrt"; }
  // The PE kernels' layout this device runs (never Auto).
  PeLayout peLayout() const { return pe_layout_; }
  // How the batches cross to the device and back.
  BatchTransfer batchTransfer() const { return transfer_; }
  void intersect(const std::vector<GrRay>& rays, HitMode mode, std::vector<GrHit>& hits,
                 RayDiagnostics* diagnostics) override;
  // Primary rays as camera bundles (camera_bundles.h): PEs receive runs of pixel tiles
  // through their voxels' screen footprints instead of per-ray 3D-DDA lists; the kernel
  // keeps the same pairs, so the same hits.
  void intersectPrimary(const PinholeView& view, const std::vector<GrRay>& rays,
                        std::vector<GrHit>& hits, RayDiagnostics* diagnostics) override;
  // The same, with the rays made a band of four rows at a time and written to the bundle
  // planes while the band is still in cache.
  void generateAndIntersectPrimary(const PinholeView& view, const CameraRayGenerator& camera,
                                   std::vector<GrRay>& rays, std::vector<GrHit>& hits,
                                   RayDiagnostics* diagnostics) override;

  // Shadow rays as light bundles (light_bundles.h): PEs receive runs of rays through
  // their voxels' outlines as seen from the point.
  void intersectTowardsPoint(const glm::vec3& point, const std::vector<GrRay>& rays, HitMode mode,
                             std::vector<GrHit>& hits) override;
  // Tests send every light batch through the bundles, whatever its size and shape.
  void forceLightBundles() { force_light_bundles_ = true; }
  // Light culling (light_culling.h) on or off for later batches towards a point; on by
  // default. For tests: off, the light bundles' kernels use segment culling.
  void allowLightCulling(bool allowed) { light_culling_allowed_ = allowed; }
  // Which batches run with the interrupt chain.
  bool cameraInterrupt() const { return interrupt_ != PeInterrupt::Off; }
  bool allInterrupt() const { return interrupt_ == PeInterrupt::AllRays; }
  // The most bytes one batch's pairs or results buffer may take: by default the device's
  // largest buffer (CL_DEVICE_MAX_MEM_ALLOC_SIZE), at most 1 / kBatchMemoryShare of its
  // global memory. A batch that would need more runs in parts (bundle tasks in chunks,
  // list batches split by rays) with the same hits; tests set a small limit.
  void setBatchBufferLimit(size_t bytes);
  size_t batchBufferLimit() const { return batch_buffer_limit_; }
  // Whether the last bundle batch ran with packet culling (for tests).
  bool packetCullingUsed() const { return packet_culling_used_; }

  // Rays and tests each PE received, summed over all batches (load balance).
  const std::vector<uint64_t>& raysPerPe() const { return rays_per_pe_; }
  const std::vector<uint64_t>& testsPerPe() const { return tests_per_pe_; }
  // Longest traversal list seen. The camera path counts list lengths only when per-ray
  // diagnostics are asked for (it never builds per-ray lists), so false means "unknown".
  bool maxListLengthKnown() const { return list_length_known_; }
  uint64_t maxListLength() const { return max_list_length_; }

 private:
  ClRuntime& rt_;
  const UniformGrid& grid_;
  PeInterrupt interrupt_;
  PeLayout pe_layout_;
  BatchTransfer transfer_;
  bool copying() const { return transfer_ == BatchTransfer::Copy; }
  // Work-items per PE work-group: kPeLocalSize packets, of one or GR_PACKET_LANES items.
  int peLocalSize() const {
    return pe_layout_ == PeLayout::Lanes ? kPeLocalSize * GR_PACKET_LANES : kPeLocalSize;
  }
  // gridrt_lists.cl's gridrt_lists: the list path's pair packets.
  struct ListsKernelArgs {
    cl::Buffer tasks, pairs, pe_tri_begin, pe_tris, results;
    int lanes_total;
    cl::Buffer first_hit_key;
    int any_hit, interrupt;
    cl::Buffer seg_planes;
    int seg_stride;
    auto inOrder() const {
      return std::tie(tasks, pairs, pe_tri_begin, pe_tris, results, lanes_total, first_hit_key,
                      any_hit, interrupt, seg_planes, seg_stride);
    }
  };
  // gridrt_bundles.cl's gridrt_bundles: the ray bundles' planes.
  struct BundlesKernelArgs {
    cl::Buffer tasks, planes;
    int stride, common_origin;
    GrRay common;
    GrGridInfo grid;
    cl::Buffer pe_box, pe_tri_begin, pe_tris, results;
    int lanes;
    cl::Buffer first_hit_key;
    int any_hit, interrupt;
    GrCullFrame cull;
    cl::Buffer cull_planes;
    int cull_stride;
    cl::Buffer seg_planes;
    int seg_stride;
    cl::Buffer set_frames, set_planes;
    int set_stride, sets_enabled;
    auto inOrder() const {
      return std::tie(tasks, planes, stride, common_origin, common, grid, pe_box, pe_tri_begin,
                      pe_tris, results, lanes, first_hit_key, any_hit, interrupt, cull, cull_planes,
                      cull_stride, seg_planes, seg_stride, set_frames, set_planes, set_stride,
                      sets_enabled);
    }
  };
  KernelCall<ListsKernelArgs> kernel_;
  TraversalLists lists_;
  PeBins bins_;
  // Phase 1's results, mapped from the device buffers (no copy on a CPU device) for phase
  // 2 and unmapped with the next batch's device commands (an unmap on its own costs a
  // wait of its own); null when not mapped. With BatchTransfer::Copy the three point into
  // the host arrays below instead, and the unmaps only forget them.
  const float* results_map_ = nullptr;  // results_, either path
  // The bundle planes (planes_, all its capacity), mapped for writing at the end of each
  // bundle batch for the next one; null when not mapped.
  float* planes_map_ = nullptr;
  // The same for the list path's pair packets (entries_): binByPe writes them there.
  float* entries_map_ = nullptr;
  // BatchTransfer::Copy: the planes, pairs and results in host memory, kept between
  // batches (grown, never shrunk, so their pages are not faulted in again every batch).
  std::vector<float> planes_host_, entries_host_, results_host_;
  // Enqueue the unmaps of phase 1's results, of the planes and of the pairs (inside
  // ClRuntime::runAndWait).
  void enqueueUnmaps();
  void enqueuePlanesUnmap();
  void enqueueEntriesUnmap();
  // Where the host writes a batch's planes or pairs: `buffer` made room for `floats` and
  // mapped whole for writing, or (Copy) its host array grown to the same room. Inside
  // ClRuntime::runAndWait.
  float* enqueueWritable(DeviceBuffer<float>& buffer, std::vector<float>& host, size_t floats);
  // Copy: enqueues the copy of `floats` floats from `host` to `buffer` at float `offset`
  // (nothing with Map: the unmap hands the buffer over).
  void enqueueUpload(DeviceBuffer<float>& buffer, const std::vector<float>& host, size_t offset,
                     size_t floats);
  // Phase 1's `floats` result floats for the host: mapped for reading, or (Copy) copied
  // into results_host_. Inside ClRuntime::runAndWait, after the kernel.
  const float* enqueueResultsRead(size_t floats);
  // The events of the maps, unmaps and copies enqueued since the last countTransfers, which
  // adds their device time to the counters (after the runAndWait that ran them).
  std::vector<cl::Event> transfers_;
  cl::Event* nextTransfer();
  void countTransfers();
  std::vector<uint64_t> rays_per_pe_, tests_per_pe_;
  uint64_t max_list_length_ = 0;
  bool list_length_known_ = true;
  size_t batch_buffer_limit_ = 0;
  // Whether a list batch of `pairs` pairs fits batch_buffer_limit_ and int lane indices.
  bool pairsFit(size_t pairs) const;
  // A list batch too large for the device, traced in two halves of its rays (each split
  // again as needed).
  void intersectInParts(const std::vector<GrRay>& rays, HitMode mode, std::vector<GrHit>& hits,
                        RayDiagnostics* diagnostics);

  // Phase 1: runs one work-group per task (bins_.tasks) on the batch's pair packets,
  // already in entries_ through entries_map_ (with their rays; copied there first with
  // BatchTransfer::Copy); results_map_ maps their results (GR_LIST_RESULT_PLANES planes,
  // then the packets' masks) or points at their copy.
  void runPes(size_t rays, HitMode mode);
  // The end of a batch, for both paths: adds the batch to the PE load and the counters
  // (phase 1's results stay mapped until the next batch's device commands).
  void finishBatch(const std::vector<int>& pairs_per_pe, size_t rays, uint64_t tests,
                   uint64_t tests_run, size_t pairs, uint64_t skipped);
  // The bundle path: rays in bundle order, one work-group per task, then phase 2 over
  // the packets' masks (the first PE of a ray's list with a hit holds its smallest t).
  // cull_frame (may be null): packet culling (packet_culling.h) on that frame, used when
  // the rays share an origin and the frame covers them all.
  // fill (may be null) writes the direction planes itself (and makes `rays` first, as it
  // goes), counting the rays that do not start where `common` does and those the culling
  // frame does not cover; by default they are gathered from `rays`.
  struct PlaneFill {
    GrRay common;  // the start every ray should share
    std::function<void(float* planes, size_t stride, int& differing, int& uncovered)> write;
  };
  // interrupt: the kernel skips lanes an earlier PE has hit (the batch's bundles put
  // nearer PEs first, camera_bundles.h).
  // light_culling: the tasks' cull_set faces use light_cull_cache_'s boxes (uploaded).
  void intersectBundles(const std::vector<GrRay>& rays, const RayBundles& bundles, HitMode mode,
                        bool interrupt, std::vector<GrHit>& hits, RayDiagnostics* diagnostics,
                        const GrCullFrame* cull_frame = nullptr, const PlaneFill* fill = nullptr,
                        bool light_culling = false);
  // The frame the kernel gets for this batch (enabled 0 unless culling is allowed: common
  // origin, every ray covered by the frame); uploads the PE triangles' boxes when they
  // changed.
  GrCullFrame prepareCulling(bool allowed, const GrCullFrame& frame, const GrRay& common);
  RayBundles camera_bundles_;
  CameraBundleScratch camera_scratch_;
  std::vector<std::vector<float>> camera_rows_;  // per thread: one row's directions (x, y, z)
  bool force_light_bundles_ = false;
  bool light_culling_allowed_ = true;
  bool packet_culling_used_ = false;
  RayBundles light_bundles_;
  LightBundleScratch light_scratch_;
  std::vector<std::vector<int>> thread_pe_pairs_;  // per thread, pairs per PE
  // The list path's phase 2: the result lanes slice `from` found for the rays of slice
  // `to`, at [from * slices + to] (kept between batches).
  struct SentLane {
    uint32_t lane;  // result lane
    int32_t pe;     // its PE; -1 - pe for a lane the interrupt skipped (diagnostics)
    int32_t ray;
  };
  std::vector<std::vector<SentLane>> sent_lanes_;
  // Packet culling: the PE triangles' boxes (in pe_triangles order) and their device copy.
  CullPlaneCache cull_cache_;
  DeviceBuffer<float> cull_planes_{"the culling boxes", CL_MEM_READ_ONLY};
  // Light culling (light_culling.h): each cube face's frame and boxes, and their copies.
  LightCullCache light_cull_cache_;
  DeviceBuffer<float> light_cull_planes_{"the light culling boxes", CL_MEM_READ_ONLY};
  DeviceBuffer<GrCullFrame> light_cull_frames_{"the light culling frames", CL_MEM_READ_ONLY};
  // Segment culling: the PE triangles' planes (segment_culling.h), uploaded once.
  DeviceBuffer<float> seg_planes_{"the segment culling planes", CL_MEM_READ_ONLY};
  int seg_stride_ = 0;
  DeviceBuffer<float> pe_box_{"the PE boxes", CL_MEM_READ_ONLY};
  DeviceBuffer<float> planes_{"the ray bundle", CL_MEM_READ_ONLY};
  DeviceBuffer<GrBundleTask> bundle_tasks_{"the bundle tasks", CL_MEM_READ_ONLY};
  // Phase 1's results of either path (GR_RESULT_*): planes per lane, then packet masks.
  DeviceBuffer<float> results_{"the per-PE results", CL_MEM_WRITE_ONLY};
  KernelCall<BundlesKernelArgs> bundle_kernel_;
  DeviceBuffer<int> pe_tri_begin_{"the PE offsets", CL_MEM_READ_ONLY};
  DeviceBuffer<GrTriangle> pe_triangles_{"the PE triangles", CL_MEM_READ_ONLY};
  DeviceBuffer<float> entries_{"the PE inputs", CL_MEM_READ_ONLY};
  DeviceBuffer<GrPeTask> tasks_{"the PE tasks", CL_MEM_READ_ONLY};
  DeviceBuffer<int> first_hit_key_{"the interrupt flags", CL_MEM_READ_WRITE};
};

}  // namespace gridrt
