#include "gridrt_intersector.h"

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstring>
#include <numeric>

#include "parallel_loops.h"
#include "prepared_triangles.h"
#include "ray_tests.h"
#include "segment_culling.h"
#include "stopwatch.h"

namespace gridrt {

namespace {

// How many slots of bundle order ahead the plane pass fetches its rays: the shadow rays'
// planes of a default Whitted frame 1.60 -> 0.90 ms warm at 64 (16: 1.29; 128, 256: no
// better than 64).
constexpr size_t kPlaneFetchAhead = 64;

// One parallel slice's counts of a batch's phase 2, summed once all slices are done.
// A cache line each: the slices update theirs for every packet, and neighbours on one
// line made the cores take it from each other (false sharing: the row of 16 bunnies'
// phase 2 spent a tenth of its samples on the tallies' stores).
struct alignas(64) SliceTally {
  uint64_t tests = 0, tests_run = 0, skipped = 0, pairs = 0, longest = 0;
  static SliceTally sumOf(const std::vector<SliceTally>& slices) {
    SliceTally sum;
    for (const SliceTally& t : slices) {
      sum.tests += t.tests;
      sum.tests_run += t.tests_run;
      sum.skipped += t.skipped;
      sum.pairs += t.pairs;
      sum.longest = std::max(sum.longest, t.longest);
    }
    return sum;
  }
};

// Maps `count` elements of a device buffer into host memory (no copy on a CPU device).
// Non-blocking: the pointer is usable once the enclosing runAndWait returns.
template <typename T>
T* mapBuffer(ClRuntime& rt, cl::Buffer& buffer, cl_map_flags flags, size_t count, cl::Event* done) {
  return static_cast<T*>(rt.queue().enqueueMapBuffer(
      buffer, CL_FALSE, flags, 0, std::max<size_t>(count, 1) * sizeof(T), nullptr, done));
}

int popcount(int bits) { return __builtin_popcount(unsigned(bits)); }

// Phase 1's results of one batch as the host reads them (GR_RESULT_*, gridrt_types.h).
struct PacketResults {
  const float *t = nullptr, *u = nullptr, *v = nullptr;
  const int *prim = nullptr, *ray = nullptr;  // ray: the list kernel's only
  const GrPacketMasks* masks = nullptr;
  PacketResults(const float* results, size_t lanes, int planes) {
    if (!results) return;
    t = results + GR_RESULT_T * lanes;
    prim = reinterpret_cast<const int*>(results + GR_RESULT_PRIM * lanes);
    u = results + GR_RESULT_U * lanes;
    v = results + GR_RESULT_V * lanes;
    if (planes > GR_RESULT_RAY) ray = reinterpret_cast<const int*>(results + GR_RESULT_RAY * lanes);
    masks = reinterpret_cast<const GrPacketMasks*>(results + size_t(planes) * lanes);
  }
  // Phase 2's rule, for both paths: a ray keeps the smallest (t, prim) over its PEs'
  // in-voxel hits. Hits lie in their own voxels, disjoint intervals of the ray, so this is
  // the hit of the first PE in the ray's list that has one (the paper's rule); on an exact
  // tie at a shared boundary the lower triangle index wins, as for every intersector.
  // Equal (t, prim) from two PEs (one hit on their shared boundary) is the same hit: the
  // lower PE is named the winner (winner may be null).
  void keepNearer(size_t lane, int pe, GrHit& best, int* winner) const {
    const float hit_t = t[lane];
    const int hit_prim = prim[lane];
    const bool same = hit_t == best.t && hit_prim == best.prim;
    if (hit_t < best.t || (hit_t == best.t && hit_prim < best.prim) ||
        (same && winner && pe < *winner)) {
      best = GrHit{hit_t, hit_prim, u[lane], v[lane]};
      if (winner) *winner = pe;
    }
  }
  // Phase 2 for the lanes of `hit_bits` of one packet of PE `pe`, whose lane 0 is result
  // lane `first`: each lane's ray (ray_of(lane); -1 for a ray another thread reduces)
  // keeps the nearer of its hit and the lane's (keepNearer); winners may be null.
  template <typename RayOfLane>
  void reduceHits(int hit_bits, size_t first, int pe, RayOfLane ray_of, std::vector<GrHit>& hits,
                  std::vector<int>* winners) const {
    for (int bits = hit_bits; bits; bits &= bits - 1) {
      const int lane = __builtin_ctz(unsigned(bits));
      const int ray = ray_of(lane);
      if (ray >= 0)
        keepNearer(first + size_t(lane), pe, hits[ray], winners ? &(*winners)[ray] : nullptr);
    }
  }
};

}  // namespace

GridRtIntersector::GridRtIntersector(ClRuntime& runtime, const UniformGrid& grid,
                                     PeInterrupt interrupt, const KernelOptions& kernel_options)
    : rt_(runtime),
      grid_(grid),
      interrupt_(interrupt),
      pe_layout_(peLayoutFor(kernel_options.pe_layout, runtime.info())),
      transfer_(kernel_options.transfer) {
  const std::string defines = "-DGR_PE_LOCAL_SIZE=" + std::to_string(kPeLocalSize) + " " +
                              segmentCullDefines() + " " + kernel_options.defines();
  const std::string suffix = pe_layout_ == PeLayout::Lanes ? "_lanes" : "";
  kernel_ = KernelCall<ListsKernelArgs>(rt_.program("gridrt_lists" + suffix + ".cl", defines),
                                        "gridrt_lists" + suffix);
  bundle_kernel_ = KernelCall<BundlesKernelArgs>(
      rt_.program("gridrt_bundles" + suffix + ".cl", defines), "gridrt_bundles" + suffix);
  checkTriangleLayout(grid.pe_triangles, kernel_options);
  pe_tri_begin_.uploadNow(rt_, grid.pe_tri_begin);
  pe_box_.uploadNow(rt_, grid.pe_hull.empty() ? grid.pe_box : grid.pe_hull);
  // Copied on all cores into the mapped buffer (tens of MB on a large scene).
  pe_triangles_.fillMapped(rt_, grid.pe_triangles.size(), [&](GrTriangle* out) {
    parallelSlices(parallelSliceCount(), [&](int me, int slices) {
      const auto [first, last] = sliceRange(grid.pe_triangles.size(), me, slices);
      std::copy(grid.pe_triangles.begin() + first, grid.pe_triangles.begin() + last, out + first);
    });
  });
  const size_t seg_stride = grid.pe_triangles.size() + kSegmentCullPlanePadding;
  seg_planes_.fillMapped(rt_, GR_SEG_PLANES * seg_stride, [&](float* planes) {
    writeSegmentCullPlanes(grid.pe_triangles.data(), grid.pe_triangles.size(), planes);
  });
  seg_stride_ = int(seg_stride);
  rays_per_pe_.assign(grid.peCount(), 0);
  tests_per_pe_.assign(grid.peCount(), 0);
  const DeviceInfo& device = rt_.info();
  setBatchBufferLimit(std::min<unsigned long long>(device.max_alloc_bytes,
                                                   device.global_mem_bytes / kBatchMemoryShare));
}

void GridRtIntersector::setBatchBufferLimit(size_t bytes) {
  batch_buffer_limit_ = std::max<size_t>(bytes, 1);
  // The bundle results take GR_BUNDLE_RESULT_PLANES floats a lane and a packet's masks.
  const size_t lane_bytes = GR_BUNDLE_RESULT_PLANES * sizeof(float) + 1;
  const size_t lanes = std::max<size_t>(batch_buffer_limit_ / lane_bytes, GR_PACKET_LANES);
  camera_bundles_.max_chunk_lanes = light_bundles_.max_chunk_lanes = lanes;
}

bool GridRtIntersector::pairsFit(size_t pairs) const {
  const size_t packets = maxPairPackets(pairs, grid_.peCount());
  const size_t lanes = packets * GR_PACKET_LANES;
  const size_t pair_bytes = packets * kPairPacketFloats * sizeof(float);
  const size_t result_bytes = (GR_LIST_RESULT_PLANES * lanes + 4 * packets) * sizeof(float);
  return lanes < size_t(INT_MAX) && pair_bytes <= batch_buffer_limit_ &&
         result_bytes <= batch_buffer_limit_;
}

void GridRtIntersector::intersectInParts(const std::vector<GrRay>& rays, HitMode mode,
                                         std::vector<GrHit>& hits, RayDiagnostics* diagnostics) {
  // Halves in ray order; each half splits again while its pairs do not fit. A ray's hit
  // depends on its own list only, so the hits are the same as in one batch.
  const size_t n = rays.size(), half = n / 2;
  hits.resize(n);
  if (diagnostics) {
    diagnostics->tests.assign(n, 0);
    diagnostics->winning_pe.assign(n, -1);
    diagnostics->list_length.assign(n, 0);
  }
  std::vector<GrRay> part;
  std::vector<GrHit> part_hits;
  RayDiagnostics part_diagnostics;
  for (size_t first : {size_t(0), half}) {
    const size_t last = first == 0 ? half : n;
    part.assign(rays.begin() + first, rays.begin() + last);
    intersect(part, mode, part_hits, diagnostics ? &part_diagnostics : nullptr);
    std::copy(part_hits.begin(), part_hits.end(), hits.begin() + first);
    if (diagnostics) {
      std::copy(part_diagnostics.tests.begin(), part_diagnostics.tests.end(),
                diagnostics->tests.begin() + first);
      std::copy(part_diagnostics.winning_pe.begin(), part_diagnostics.winning_pe.end(),
                diagnostics->winning_pe.begin() + first);
      std::copy(part_diagnostics.list_length.begin(), part_diagnostics.list_length.end(),
                diagnostics->list_length.begin() + first);
    }
  }
}

void GridRtIntersector::runPes(size_t n, HitMode mode) {
  const std::vector<GrPeTask>& tasks = bins_.tasks;
  const size_t lanes = bins_.packets * GR_PACKET_LANES;
  const size_t result_floats = GR_LIST_RESULT_PLANES * lanes + 4 * bins_.packets;
  cl::Event pe_run;
  rt_.runAndWait([&] {
    enqueueUnmaps();
    enqueueEntriesUnmap();
    if (tasks.empty()) return;
    tasks_.upload(rt_, tasks);
    results_.reserve(rt_, result_floats);
    first_hit_key_.reserve(rt_, n);
    if (allInterrupt())
      rt_.queue().enqueueFillBuffer(first_hit_key_.get(), int(INT_MAX), 0, n * sizeof(int));
    enqueueUpload(entries_, entries_host_, 0, bins_.packets * kPairPacketFloats);
    ListsKernelArgs args;
    args.tasks = tasks_.get();
    args.pairs = entries_.get();
    args.pe_tri_begin = pe_tri_begin_.get();
    args.pe_tris = pe_triangles_.get();
    args.results = results_.get();
    args.lanes_total = int(lanes);
    args.first_hit_key = first_hit_key_.get();
    args.any_hit = mode == HitMode::AnyHit ? 1 : 0;
    args.interrupt = allInterrupt() ? 1 : 0;
    args.seg_planes = seg_planes_.get();
    args.seg_stride = seg_stride_;
    kernel_.enqueue(rt_.queue(), cl::NDRange(tasks.size() * peLocalSize()),
                    cl::NDRange(peLocalSize()), args, &pe_run);
    results_map_ = enqueueResultsRead(result_floats);
    // Mapped again for the next batch's pairs once the kernel has read them.
    entries_map_ = enqueueWritable(entries_, entries_host_, entries_.capacity());
  });
  countTransfers();
  counters_.device_ms += eventMs(pe_run);
}

GridRtIntersector::~GridRtIntersector() {
  if (!results_map_ && !planes_map_ && !entries_map_) return;
  try {
    rt_.runAndWait([&] {
      enqueueUnmaps();
      enqueuePlanesUnmap();
      enqueueEntriesUnmap();
    });
  } catch (...) {
    // The context goes with the runtime anyway.
  }
}

void GridRtIntersector::enqueueUnmaps() {
  if (results_map_ && !copying())
    rt_.queue().enqueueUnmapMemObject(results_.get(), const_cast<float*>(results_map_), nullptr,
                                      nextTransfer());
  results_map_ = nullptr;
}

void GridRtIntersector::enqueueEntriesUnmap() {
  if (entries_map_ && !copying())
    rt_.queue().enqueueUnmapMemObject(entries_.get(), entries_map_, nullptr, nextTransfer());
  entries_map_ = nullptr;
}

void GridRtIntersector::enqueuePlanesUnmap() {
  if (planes_map_ && !copying())
    rt_.queue().enqueueUnmapMemObject(planes_.get(), planes_map_, nullptr, nextTransfer());
  planes_map_ = nullptr;
}

float* GridRtIntersector::enqueueWritable(DeviceBuffer<float>& buffer, std::vector<float>& host,
                                          size_t floats) {
  buffer.reserve(rt_, floats);
  if (!copying())
    return mapBuffer<float>(rt_, buffer.get(), CL_MAP_WRITE_INVALIDATE_REGION, buffer.capacity(),
                            nextTransfer());
  if (host.size() < buffer.capacity()) host.resize(buffer.capacity());
  return host.data();
}

void GridRtIntersector::enqueueUpload(DeviceBuffer<float>& buffer, const std::vector<float>& host,
                                      size_t offset, size_t floats) {
  if (!copying() || floats == 0) return;
  // Non-blocking: `host` is not written again before runAndWait has waited for the copy.
  rt_.queue().enqueueWriteBuffer(buffer.get(), CL_FALSE, offset * sizeof(float),
                                 floats * sizeof(float), host.data() + offset, nullptr,
                                 nextTransfer());
}

cl::Event* GridRtIntersector::nextTransfer() { return &transfers_.emplace_back(); }

void GridRtIntersector::countTransfers() {
  for (const cl::Event& done : transfers_) counters_.transfer_ms += eventMs(done);
  transfers_.clear();
}

const float* GridRtIntersector::enqueueResultsRead(size_t floats) {
  if (!copying()) return mapBuffer<float>(rt_, results_.get(), CL_MAP_READ, floats, nextTransfer());
  if (results_host_.size() < floats) results_host_.resize(std::max(floats, results_.capacity()));
  if (floats)
    rt_.queue().enqueueReadBuffer(results_.get(), CL_FALSE, 0, floats * sizeof(float),
                                  results_host_.data(), nullptr, nextTransfer());
  return results_host_.data();
}

void GridRtIntersector::finishBatch(const std::vector<int>& pairs_per_pe, size_t rays,
                                    uint64_t tests, uint64_t tests_run, size_t pairs,
                                    uint64_t skipped) {
  for (int pe = 0; pe < grid_.peCount(); ++pe) {
    rays_per_pe_[pe] += pairs_per_pe[pe];
    tests_per_pe_[pe] += uint64_t(pairs_per_pe[pe]) * grid_.triangleCountOfPe(pe);
  }
  counters_.rays += rays;
  counters_.tests += tests;
  counters_.tests_run += tests_run;
  counters_.list_entries += pairs;
  counters_.skipped_pairs += skipped;
}

void GridRtIntersector::intersect(const std::vector<GrRay>& rays, HitMode mode,
                                  std::vector<GrHit>& hits, RayDiagnostics* diagnostics) {
  const size_t n = rays.size();
  hits.resize(n);
  Stopwatch clock;
  if (n > size_t(GR_PAIR_MAX_RAYS)) {  // more rays than a pair can name
    ++counters_.split_batches;
    intersectInParts(rays, mode, hits, diagnostics);
    return;
  }
  computeTraversalLists(grid_, rays.data(), n, lists_);
  counters_.walk_ms += clock.ms();
  if (n > 1 && !pairsFit(lists_.entryCount())) {
    ++counters_.split_batches;
    intersectInParts(rays, mode, hits, diagnostics);
    return;
  }
  clock.restart();
  // The pairs go straight into the device buffer, left mapped by the previous batch.
  const size_t pair_floats =
      maxPairPackets(lists_.entryCount(), grid_.peCount()) * kPairPacketFloats;
  if (!entries_map_ || entries_.capacity() < pair_floats) {
    rt_.runAndWait([&] {
      enqueueUnmaps();
      enqueueEntriesUnmap();
      entries_map_ = enqueueWritable(entries_, entries_host_, pair_floats);
    });
    countTransfers();
  }
  binByPe(lists_, rays.data(), grid_.peCount(), kPeTaskRays, bins_, entries_map_);
  counters_.binning_ms += clock.ms();

  clock.restart();
  runPes(n, mode);
  counters_.kernel_ms += clock.ms();
  counters_.packets += bins_.packets;

  // Phase 2: per ray, the smallest (t, prim) over its PEs' in-voxel hits
  // (PacketResults::keepNearer), in two steps that read each result once whatever the
  // thread count: each slice takes the tasks whose packets start in its share of the
  // packets, counts their tests and sends each hit lane to the slice that owns its ray;
  // then each slice reduces what was sent to its rays. keepNearer is a total order on (t, prim,
  // PE), so the hits do not depend on the order the lanes arrive in.
  clock.restart();
  if (diagnostics) {
    diagnostics->tests.assign(n, 0);
    diagnostics->winning_pe.assign(n, -1);
    diagnostics->list_length.assign(n, 0);
  }
  const PacketResults results(results_map_, bins_.packets * GR_PACKET_LANES, GR_LIST_RESULT_PLANES);
  const std::vector<GrPeTask>& tasks = bins_.tasks;
  const int slices = parallelSliceCount();
  std::vector<SliceTally> tallies(slices);
  sent_lanes_.resize(size_t(slices) * size_t(slices));
  const size_t rays_per_slice = std::max<size_t>(1, (n + size_t(slices) - 1) / size_t(slices));
  parallelSlices(slices, [&](int me, int count) {
    SliceTally& tally = tallies[me];
    for (int to = 0; to < count; ++to) sent_lanes_[size_t(me) * count + to].clear();
    const auto [packet_lo, packet_hi] = sliceRange(bins_.packets, me, count);
    for (const GrPeTask& task : tasks) {
      if (size_t(task.first_packet) < packet_lo || size_t(task.first_packet) >= packet_hi) continue;
      const int cost = grid_.triangleCountOfPe(task.pe);
      const int packets = (task.pair_count + GR_PACKET_LANES - 1) / GR_PACKET_LANES;
      for (int p = task.first_packet; p < task.first_packet + packets; ++p) {
        const GrPacketMasks& m = results.masks[p];
        tally.tests += uint64_t(popcount(m.pierced & ~m.skipped)) * cost;
        tally.tests_run += uint64_t(m.tests);
        tally.skipped += popcount(m.skipped);
        const uint32_t first = uint32_t(p) * GR_PACKET_LANES;
        auto send = [&](int bits, int32_t pe) {
          for (; bits; bits &= bits - 1) {
            const uint32_t lane = first + uint32_t(__builtin_ctz(unsigned(bits)));
            const int32_t ray = results.ray[lane];
            sent_lanes_[size_t(me) * count + size_t(ray) / rays_per_slice].push_back(
                SentLane{lane, pe, ray});
          }
        };
        send(m.hit & ~m.skipped, task.pe);
      }
    }
  });
  parallelSlices(slices, [&](int me, int count) {
    SliceTally& tally = tallies[me];
    const size_t lo = std::min(n, size_t(me) * rays_per_slice);
    const size_t hi = std::min(n, lo + rays_per_slice);
    for (size_t r = lo; r < hi; ++r) {
      hits[r] = GrHit{rays[r].tmax, -1, 0.0f, 0.0f};
      const int length = lists_.lengthOf(r);
      tally.longest = std::max<uint64_t>(tally.longest, uint64_t(length));
      if (diagnostics) diagnostics->list_length[r] = length;
    }
    std::vector<int>* winners = diagnostics ? &diagnostics->winning_pe : nullptr;
    for (int from = 0; from < count; ++from)
      for (const SentLane& sent : sent_lanes_[size_t(from) * count + me])
        results.keepNearer(sent.lane, sent.pe, hits[sent.ray],
                           winners ? &(*winners)[sent.ray] : nullptr);
    if (diagnostics)
      for (size_t r = lo; r < hi; ++r)
        diagnostics->tests[r] = testsToWinnerInList(grid_, lists_.entriesOf(r), lists_.lengthOf(r),
                                                    diagnostics->winning_pe[r]);
  });
  const SliceTally sum = SliceTally::sumOf(tallies);
  max_list_length_ = std::max(max_list_length_, sum.longest);
  finishBatch(bins_.pairs_per_pe, n, sum.tests, sum.tests_run, lists_.entryCount(), sum.skipped);
  counters_.reduce_ms += clock.ms();
}

void GridRtIntersector::intersectPrimary(const PinholeView& view, const std::vector<GrRay>& rays,
                                         std::vector<GrHit>& hits, RayDiagnostics* diagnostics) {
  Stopwatch clock;
  bundleCameraRays(grid_, view, camera_bundles_, cameraInterrupt(), camera_scratch_);
  counters_.bundling_ms += clock.ms();
  const GrCullFrame frame = cullFrameOf(view);
  intersectBundles(rays, camera_bundles_, HitMode::Closest, cameraInterrupt(), hits, diagnostics,
                   &frame);
}

void GridRtIntersector::intersectTowardsPoint(const glm::vec3& point,
                                              const std::vector<GrRay>& rays, HitMode mode,
                                              std::vector<GrHit>& hits) {
  if (!force_light_bundles_ && rays.size() < kMinLightBundleRays) {
    intersect(rays, mode, hits, nullptr);
    return;
  }
  Stopwatch clock;
  const LightRayBounds bounds =
      bundleLightRays(grid_, point, rays.data(), rays.size(), light_bundles_, light_scratch_);
  if (!force_light_bundles_ &&
      light_bundles_.out_lanes > kMaxLightBundleLanesPerRay * rays.size()) {
    counters_.bundling_ms += clock.ms();
    intersect(rays, mode, hits, nullptr);
    return;
  }
  TowardsOrigin towards;
  towards.miss = bounds.miss;
  towards.ray_reach = bounds.reach;
  towards.min_length = bounds.min_length;
  const bool light_culling = light_culling_allowed_ && LightCullCache::usable(towards);
  if (light_culling &&
      light_cull_cache_.update(point, towards, bounds.faces, grid_.pe_triangles.data(),
                               grid_.pe_triangles.size())) {
    light_cull_planes_.uploadNow(rt_, light_cull_cache_.planes());
    light_cull_frames_.upload(rt_, light_cull_cache_.frames().data(), 6);
  }
  counters_.bundling_ms += clock.ms();
  intersectBundles(rays, light_bundles_, mode, allInterrupt(), hits, nullptr, nullptr, nullptr,
                   light_culling);
}

GrCullFrame GridRtIntersector::prepareCulling(bool allowed, const GrCullFrame& frame,
                                              const GrRay& common) {
  // Culling needs every hit at t > 0 in front of the origin (packet_culling.h).
  if (!allowed || !(common.tmin >= 0.0f)) return GrCullFrame{};
  const glm::vec3 origin(common.ox, common.oy, common.oz);
  if (cull_cache_.update(frame, origin, grid_.pe_triangles.data(), grid_.pe_triangles.size()))
    cull_planes_.uploadNow(rt_, cull_cache_.planes());
  return frame;
}

void GridRtIntersector::generateAndIntersectPrimary(const PinholeView& view,
                                                    const CameraRayGenerator& camera,
                                                    std::vector<GrRay>& rays,
                                                    std::vector<GrHit>& hits,
                                                    RayDiagnostics* diagnostics) {
  // Rays of a camera without one eye: made first, then traced as any batch of them.
  if (!camera.pinhole()) {
    Intersector::generateAndIntersectPrimary(view, camera, rays, hits, diagnostics);
    return;
  }
  Stopwatch clock;
  bundleCameraRays(grid_, view, camera_bundles_, cameraInterrupt(), camera_scratch_);
  counters_.bundling_ms += clock.ms();
  const GrCullFrame frame = cullFrameOf(view);
  const PixelWindow& w = view.window;
  const int ww = w.width(), wh = w.height();
  rays.resize(size_t(ww) * wh);
  // The camera bundles' layout (camera_bundles.h): 4x4-pixel tiles, row by row, so tile
  // row ty holds the slots [ty * tiles_x * 16, (ty + 1) * tiles_x * 16) and the pixels of
  // rows 4 ty .. 4 ty + 3 of the window.
  const int tiles_x = (ww + kTileSize - 1) / kTileSize, tiles_y = (wh + kTileSize - 1) / kTileSize;
  const size_t band_slots = size_t(tiles_x) * kTileSize * kTileSize;
  PlaneFill fill;
  fill.common = camera(w.x0, w.y0, 0.5f, 0.5f);
  fill.write = [&](float* planes, size_t stride, int& differing, int& uncovered) {
    float* dx = planes + GR_PLANE_DX * stride;
    float* dy = planes + GR_PLANE_DY * stride;
    float* dz = planes + GR_PLANE_DZ * stride;
    // Each row's directions come out of centreRow as three arrays, one tile column (4
    // lanes) after another; row ly of a tile row fills lanes 4 ly .. 4 ly + 3 of each of
    // its tiles. Past the window's right edge and bottom the lanes are padding (zero).
    const size_t row_floats = size_t(tiles_x) * kTileSize;
    camera_rows_.resize(parallelSliceCount());
    std::vector<int> slice_uncovered(camera_rows_.size(), 0);
    parallelSlices(int(camera_rows_.size()), [&](int me, int count) {
      std::vector<float>& row = camera_rows_[me];
      row.assign(3 * row_floats, 0.0f);
      float *rdx = row.data(), *rdy = rdx + row_floats, *rdz = rdy + row_floats;
      int u = 0;  // stored once at the end: the slices' counts share a cache line
      const auto [ty_begin, ty_end] = sliceRange(size_t(tiles_y), me, count);
      for (int ty = int(ty_begin); ty < int(ty_end); ++ty) {
        for (int ly = 0; ly < kTileSize; ++ly) {
          const int y = ty * kTileSize + ly;
          if (y < wh) {
            camera.centreRow(w.y0 + y, w.x0, w.x1, rays.data() + size_t(y) * ww, rdx, rdy, rdz);
            // The frame's cover (packet_culling.h).
            for (int x = 0; x < ww; ++x)
              u += !cullFrameCovers(frame, GrRay{0, 0, 0, 0, rdx[x], rdy[x], rdz[x], 0});
          } else {
            std::fill(row.begin(), row.end(), 0.0f);
          }
          const size_t b0 = size_t(ty) * band_slots + size_t(ly) * kTileSize;
          for (int tx = 0; tx < tiles_x; ++tx)
            for (int lx = 0; lx < kTileSize; ++lx) {
              const size_t b = b0 + size_t(tx) * GR_PACKET_LANES + lx,
                           x = size_t(tx) * kTileSize + lx;
              dx[b] = rdx[x];
              dy[b] = rdy[x];
              dz[b] = rdz[x];
            }
        }
      }
      slice_uncovered[me] = u;
    });
    for (size_t b = size_t(tiles_y) * band_slots; b < stride; ++b) dx[b] = dy[b] = dz[b] = 0.0f;
    // A pinhole camera's rays all start at its eye, over [0, inf) (CameraRayGenerator::pinhole).
    differing = 0;
    uncovered = std::accumulate(slice_uncovered.begin(), slice_uncovered.end(), 0);
  };
  intersectBundles(rays, camera_bundles_, HitMode::Closest, cameraInterrupt(), hits, diagnostics,
                   &frame, &fill);
}

void GridRtIntersector::intersectBundles(const std::vector<GrRay>& rays, const RayBundles& bundles,
                                         HitMode mode, bool interrupt, std::vector<GrHit>& hits,
                                         RayDiagnostics* diagnostics, const GrCullFrame* cull_frame,
                                         const PlaneFill* fill, bool light_culling) {
  const size_t n = rays.size();
  hits.resize(n);
  const size_t slots = bundles.ray_of.size();
  // A packet may read up to 15 rays past its task's end: one packet of padding.
  const size_t stride = slots + GR_PACKET_LANES;
  Stopwatch clock;

  // Phase 1: the rays in bundle order, as planes, straight into the device buffer: the
  // directions always (a zero direction marks padding); origins and intervals only when
  // the rays do not all share those of the first ray (camera rays do). Rays without a
  // culling frame (shadow rays: each from its own hit point) get all planes in one pass.
  // The previous bundle batch left the buffer mapped for this one: a map of its own
  // would cost a wait on the device.
  float* planes = planes_map_;
  if (!planes || planes_.capacity() < GR_PLANES * stride) {
    rt_.runAndWait([&] {
      enqueueUnmaps();
      enqueuePlanesUnmap();
      planes = planes_map_ = enqueueWritable(planes_, planes_host_, GR_PLANES * stride);
    });
    countTransfers();
  }
  int differing = 0, uncovered = 0;
  if (fill) fill->write(planes, stride, differing, uncovered);
  const GrRay common = fill ? fill->common : n ? rays[0] : GrRay{};
  auto sameStart = [&](const GrRay& r) {
    return r.ox == common.ox && r.oy == common.oy && r.oz == common.oz && r.tmin == common.tmin &&
           r.tmax == common.tmax;
  };
  // Rays off the culling frame's forward count as uncovered (padding does not count);
  // without a frame (light bundles) nothing is checked.
  const bool check_cover = cull_frame != nullptr;
  const GrCullFrame frame = check_cover ? *cull_frame : GrCullFrame{};
  auto writeStarts = [&](long long b, const GrRay& ray) {
    planes[GR_PLANE_OX * stride + b] = ray.ox;
    planes[GR_PLANE_OY * stride + b] = ray.oy;
    planes[GR_PLANE_OZ * stride + b] = ray.oz;
    planes[GR_PLANE_TMIN * stride + b] = ray.tmin;
    planes[GR_PLANE_TMAX * stride + b] = ray.tmax;
  };
  if (check_cover && !fill) {
    // In ray order (sequential reads; the bundle order holds every ray once, and padding).
    std::vector<std::pair<int, int>> slice_counts(parallelSliceCount());
    parallelSlices(int(slice_counts.size()), [&](int me, int count) {
      const auto [begin, end] = sliceRange(n, me, count);
      int d = 0, u = 0;
#pragma omp simd reduction(+ : d, u)
      for (size_t r = begin; r < end; ++r) {
        d += !sameStart(rays[r]);
        u += !cullFrameCovers(frame, rays[r]);
      }
      slice_counts[me] = {d, u};
    });
    for (const auto& [d, u] : slice_counts) {
      differing += d;
      uncovered += u;
    }
  }
  if (!fill) {
    // A packet's slots at a time (ray_of's length, so the stride, is a multiple of 16):
    // its rays gathered into local planes, then each plane's 16 values stored at once.
    // One value at a time into eight planes, the stores had waited on their lines.
    static_assert(GR_PACKET_LANES == 16);
    const bool starts = !check_cover;
    parallelFor(0LL, (long long)(stride / GR_PACKET_LANES), [&](long long packet) {
      const size_t b0 = size_t(packet) * GR_PACKET_LANES;
      alignas(64) float local[GR_PLANES][GR_PACKET_LANES];
      for (int k = 0; k < GR_PACKET_LANES; ++k) {
        const size_t b = b0 + size_t(k);
        // Bundle order jumps about the batch: each ray is fetched kPlaneFetchAhead slots
        // before it is needed (the waits on these loads were most of the pass).
        if (b + kPlaneFetchAhead < slots) {
          const int ahead = bundles.ray_of[b + kPlaneFetchAhead];
          if (ahead >= 0) __builtin_prefetch(&rays[ahead]);
        }
        const int r = b < slots ? bundles.ray_of[b] : -1;
        const GrRay& ray = r >= 0 ? rays[r] : common;
        local[GR_PLANE_DX][k] = r >= 0 ? ray.dx : 0.0f;
        local[GR_PLANE_DY][k] = r >= 0 ? ray.dy : 0.0f;
        local[GR_PLANE_DZ][k] = r >= 0 ? ray.dz : 0.0f;
        local[GR_PLANE_OX][k] = ray.ox;
        local[GR_PLANE_OY][k] = ray.oy;
        local[GR_PLANE_OZ][k] = ray.oz;
        local[GR_PLANE_TMIN][k] = ray.tmin;
        local[GR_PLANE_TMAX][k] = ray.tmax;
      }
      for (int q : {GR_PLANE_DX, GR_PLANE_DY, GR_PLANE_DZ})
        std::memcpy(planes + size_t(q) * stride + b0, local[q], sizeof local[q]);
      if (starts)
        for (int q : {GR_PLANE_OX, GR_PLANE_OY, GR_PLANE_OZ, GR_PLANE_TMIN, GR_PLANE_TMAX})
          std::memcpy(planes + size_t(q) * stride + b0, local[q], sizeof local[q]);
    });
  }
  // Shadow rays (no frame) never share an origin: their starts are written above.
  const bool common_origin = check_cover && differing == 0;
  if (!common_origin && check_cover) {
    parallelFor(0LL, (long long)(stride), [&](long long b) {
      const int r = size_t(b) < slots ? bundles.ray_of[b] : -1;
      writeStarts(b, r >= 0 ? rays[r] : common);
    });
  }
  // The tasks run in chunks whose results fit the device (RayBundles::chunk_begin): each
  // chunk's kernel, then its part of phase 2. The planes stay on the device until the
  // last chunk has read them; the hits of later chunks go on from those of earlier ones.
  thread_pe_pairs_.resize(parallelSliceCount());
  std::vector<SliceTally> tallies(thread_pe_pairs_.size());
  std::vector<int>* winners = diagnostics ? &diagnostics->winning_pe : nullptr;
  // For the diagnostics, per slice the (ray, PE) pairs it read that the ray pierced: the
  // `tests` AOV counts those up to the winner once every chunk has run (ray_tests.h). A
  // ray's slot lies in one slice, so each slice holds all the pairs of its rays.
  std::vector<std::vector<PiercedPe>> slice_pierced(diagnostics ? tallies.size() : 0);
  GrCullFrame culling{};
  const size_t chunks = bundles.chunkCount();
  if (chunks > 1) ++counters_.split_batches;
  for (size_t chunk = 0; chunk < chunks; ++chunk) {
    const bool first_chunk = chunk == 0, last_chunk = chunk + 1 == chunks;
    const GrBundleTask* chunk_tasks = bundles.tasks.data() + bundles.chunk_begin[chunk];
    const size_t task_count = bundles.chunk_begin[chunk + 1] - bundles.chunk_begin[chunk];
    const size_t lanes = bundles.chunk_lanes[chunk], packets = lanes / GR_PACKET_LANES;
    if (!first_chunk) clock.restart();
    cl::Event pe_run;
    rt_.runAndWait([&] {
      enqueueUnmaps();
      if (first_chunk) {
        enqueuePlanesUnmap();
        // The planes written: the directions, and the starts unless the rays share one.
        static_assert(GR_PLANE_DY == GR_PLANE_DX + 1 && GR_PLANE_DZ == GR_PLANE_DX + 2);
        if (common_origin)
          enqueueUpload(planes_, planes_host_, GR_PLANE_DX * stride, 3 * stride);
        else
          enqueueUpload(planes_, planes_host_, 0, GR_PLANES * stride);
      }
      if (task_count == 0) return;
      bundle_tasks_.upload(rt_, chunk_tasks, task_count);
      // t, prim, u, v per lane, then the packets' masks (4 ints each): one buffer.
      const size_t result_floats = GR_BUNDLE_RESULT_PLANES * lanes + 4 * packets;
      results_.reserve(rt_, result_floats);
      first_hit_key_.reserve(rt_, stride);
      if (interrupt && first_chunk)
        rt_.queue().enqueueFillBuffer(first_hit_key_.get(), int(INT_MAX), 0, stride * sizeof(int));
      if (first_chunk) {
        culling = prepareCulling(check_cover && uncovered == 0 && common_origin, frame, common);
        packet_culling_used_ = culling.enabled != 0.0f;
      }
      BundlesKernelArgs args;
      args.tasks = bundle_tasks_.get();
      args.planes = planes_.get();
      args.stride = int(stride);
      args.common_origin = common_origin ? 1 : 0;
      args.common = common;
      args.grid = grid_.info;
      args.pe_box = pe_box_.get();
      args.pe_tri_begin = pe_tri_begin_.get();
      args.pe_tris = pe_triangles_.get();
      args.results = results_.get();
      args.lanes = int(lanes);
      args.first_hit_key = first_hit_key_.get();
      args.any_hit = mode == HitMode::AnyHit ? 1 : 0;
      args.interrupt = interrupt ? 1 : 0;
      args.cull = culling;
      args.cull_planes = cull_planes_.reserve(rt_, 1);
      args.cull_stride = int(cull_cache_.stride());
      args.seg_planes = seg_planes_.get();
      args.seg_stride = seg_stride_;
      args.set_frames = light_cull_frames_.reserve(rt_, 6);
      args.set_planes = light_cull_planes_.reserve(rt_, 1);
      args.set_stride = int(light_cull_cache_.stride());
      args.sets_enabled = light_culling ? 1 : 0;
      bundle_kernel_.enqueue(rt_.queue(), cl::NDRange(task_count * peLocalSize()),
                             cl::NDRange(peLocalSize()), args, &pe_run);
      results_map_ = enqueueResultsRead(result_floats);
      // Mapped again for the next bundle batch once the kernel has read it.
      if (last_chunk) planes_map_ = enqueueWritable(planes_, planes_host_, planes_.capacity());
    });
    countTransfers();
    const PacketResults results(results_map_, lanes, GR_BUNDLE_RESULT_PLANES);
    counters_.kernel_ms += clock.ms();
    counters_.device_ms += eventMs(pe_run);
    counters_.packets += packets;

    // Phase 2: per ray, the smallest (t, prim) over its PEs' in-voxel hits
    // (PacketResults::keepNearer). Each thread owns a range of bundle order and reads the
    // part of every task that falls in it.
    clock.restart();
    if (diagnostics && first_chunk) {
      diagnostics->tests.assign(n, 0);
      diagnostics->winning_pe.assign(n, -1);
      diagnostics->list_length.assign(n, 0);
    }
    // Every ray a miss to begin with, written in ray order (in bundle order it would be a
    // scatter), all of them before the hits below.
    if (first_chunk)
      parallelFor(size_t(0), n, [&](size_t r) {
        hits[r] = GrHit{common_origin ? common.tmax : rays[r].tmax, -1, 0.0f, 0.0f};
      });
    parallelSlices(int(tallies.size()), [&](int me, int count) {
      SliceTally& tally = tallies[me];
      std::vector<int>& pe_pairs = thread_pe_pairs_[me];
      if (first_chunk) pe_pairs.assign(grid_.peCount(), 0);
      const size_t span = (slots / GR_PACKET_LANES + count - 1) / count * GR_PACKET_LANES;
      const long long lo = (long long)std::min(slots, size_t(me) * span);
      const long long hi = (long long)std::min(slots, size_t(lo) + span);
      // Bundle order maps to distinct rays, so the slices write disjoint hits.
      for (size_t t = 0; t < task_count; ++t) {
        const GrBundleTask& task = chunk_tasks[t];
        const long long first = std::max<long long>(task.first_ray, lo);
        const long long last = std::min<long long>(task.first_ray + task.ray_count, hi);
        if (first >= last) continue;
        const int cost = grid_.triangleCountOfPe(task.pe);
        for (int p = int(first - task.first_ray) / GR_PACKET_LANES;
             p * GR_PACKET_LANES < last - task.first_ray; ++p) {
          const long long base = task.first_ray + p * GR_PACKET_LANES;
          // The lanes of this packet inside [first, last).
          int in_range = 0xFFFF;
          if (base < first) in_range &= 0xFFFF << int(first - base);
          if (base + GR_PACKET_LANES > last)
            in_range &= 0xFFFF >> int(base + GR_PACKET_LANES - last);
          const GrPacketMasks& m = results.masks[task.out_first / GR_PACKET_LANES + p];
          // A packet's tests count in the thread whose range holds its first lane.
          if (base >= lo) tally.tests_run += uint64_t(m.tests);
          const int pierced = m.pierced & in_range, tested = pierced & ~m.skipped;
          if (!pierced) continue;
          tally.pairs += popcount(pierced);
          tally.skipped += popcount(pierced & m.skipped);
          tally.tests += uint64_t(popcount(tested)) * cost;
          pe_pairs[task.pe] += popcount(pierced);
          if (diagnostics)
            for (int bits = pierced; bits; bits &= bits - 1) {
              const int ray = bundles.ray_of[base + __builtin_ctz(unsigned(bits))];
              ++diagnostics->list_length[ray];
              slice_pierced[me].push_back(PiercedPe{ray, task.pe});
            }
          results.reduceHits(
              m.hit & in_range, size_t(task.out_first + p * GR_PACKET_LANES), task.pe,
              [&](int lane) { return bundles.ray_of[base + lane]; }, hits, winners);
        }
      }
    });
    if (!last_chunk) counters_.reduce_ms += clock.ms();
  }
  if (diagnostics) {
    parallelSlices(int(slice_pierced.size()), [&](int me, int) {
      addTestsToWinner(grid_, rays, slice_pierced[me], diagnostics->winning_pe, diagnostics->tests);
    });
    list_length_known_ = true;
    for (int length : diagnostics->list_length)
      max_list_length_ = std::max<uint64_t>(max_list_length_, length);
  } else {
    list_length_known_ = false;
  }
  std::vector<int>& pe_pairs = thread_pe_pairs_[0];
  for (size_t t = 1; t < thread_pe_pairs_.size(); ++t)
    for (int pe = 0; pe < grid_.peCount(); ++pe) pe_pairs[pe] += thread_pe_pairs_[t][pe];
  const SliceTally sum = SliceTally::sumOf(tallies);
  finishBatch(pe_pairs, n, sum.tests, sum.tests_run, sum.pairs, sum.skipped);
  counters_.reduce_ms += clock.ms();
}

}  // namespace gridrt
