#include "pe_binning.h"

#include <algorithm>
#include <cstring>
#include <stdexcept>

#include "parallel_loops.h"

namespace gridrt {

namespace {

constexpr int kOctants = 8;

// 0..7 from the signs of the direction (a zero counts as positive).
int octantOf(const GrRay& ray) {
  return (ray.dx < 0.0f ? 1 : 0) | (ray.dy < 0.0f ? 2 : 0) | (ray.dz < 0.0f ? 4 : 0);
}

int roundUpToPacket(int lanes) {
  return (lanes + GR_PACKET_LANES - 1) / GR_PACKET_LANES * GR_PACKET_LANES;
}

float intBits(int value) {
  float f;
  std::memcpy(&f, &value, sizeof f);
  return f;
}

// Pair number `position` (lane position % 16 of packet position / 16).
void writePair(float* out, int position, const GrRay& ray, int r, const ListEntry& entry) {
  float* lane =
      out + size_t(position / GR_PACKET_LANES) * kPairPacketFloats + position % GR_PACKET_LANES;
  if (position % GR_PACKET_LANES == 0) {
    // A part's packets follow one another: the next one's lines are fetched for writing
    // now, sixteen of the part's pairs before they are needed (each store would
    // otherwise wait for its line: the buffer is larger than the core's cache).
    const float* next = lane + kPairPacketFloats;
    for (int q = 0; q < GR_PAIR_PLANES; ++q) __builtin_prefetch(next + q * GR_PACKET_LANES, 1, 3);
  }
  lane[gr_pair_value(GR_PAIR_OX, 0)] = ray.ox;
  lane[gr_pair_value(GR_PAIR_OY, 0)] = ray.oy;
  lane[gr_pair_value(GR_PAIR_OZ, 0)] = ray.oz;
  lane[gr_pair_value(GR_PAIR_DX, 0)] = ray.dx;
  lane[gr_pair_value(GR_PAIR_DY, 0)] = ray.dy;
  lane[gr_pair_value(GR_PAIR_DZ, 0)] = ray.dz;
  float lo, hi;
  const int open = gr_pair_bounds(ray.tmin, ray.tmax, entry.t_enter, entry.t_exit, &lo, &hi);
  lane[gr_pair_value(GR_PAIR_T_LO, 0)] = lo;
  lane[gr_pair_value(GR_PAIR_T_HI, 0)] = hi;
  lane[gr_pair_value(GR_PAIR_RAY, 0)] = intBits(r | open);
}

}  // namespace

size_t maxPairPackets(size_t pairs, int pe_count) {
  const size_t parts = size_t(pe_count) * kOctants;
  return (pairs + (GR_PACKET_LANES - 1) * std::min(pairs, parts) + GR_PACKET_LANES - 1) /
         GR_PACKET_LANES;
}

void binByPe(const TraversalLists& lists, const GrRay* rays, int pe_count, int task_rays,
             PeBins& bins, float* out) {
  if (task_rays <= 0 || task_rays % GR_PACKET_LANES != 0)
    throw std::invalid_argument("binByPe: task_rays must be a positive multiple of 16");
  if (lists.rayCount() > size_t(GR_PAIR_MAX_RAYS))
    throw std::invalid_argument("binByPe: more rays than a pair can name (GR_PAIR_MAX_RAYS)");
  const int threads = parallelSliceCount();
  const size_t ray_count = lists.rayCount();
  const int parts = pe_count * kOctants;
  bins.thread_counts.resize(threads);
  if (!out) {
    bins.pairs.assign(maxPairPackets(lists.entryCount(), pe_count) * kPairPacketFloats, 0.0f);
    out = bins.pairs.data();
  }
  int lanes_total = 0;
  parallelSlices(threads, [&](int t, int) {
    auto& counts = bins.thread_counts[t];
    counts.assign(parts, 0);
    const auto [first, last] = sliceRange(ray_count, t, threads);
    for (size_t r = first; r < last; ++r) {
      // The list read once: the counts' stores could alias it (as in the pass below).
      const int octant = octantOf(rays[r]), length = lists.lengthOf(r);
      const ListEntry* entries = lists.entriesOf(r);
      for (int e = 0; e < length; ++e) ++counts[entries[e].pe * kOctants + octant];
    }
  });
  // Exclusive prefix over (part, slice): slice t's pairs of a part follow slice t-1's;
  // every part starts a packet.
  bins.pairs_per_part.assign(parts, 0);
  int offset = 0;
  for (int part = 0; part < parts; ++part) {
    offset = roundUpToPacket(offset);
    for (int k = 0; k < threads; ++k) {
      int c = bins.thread_counts[k][part];
      bins.thread_counts[k][part] = offset;
      offset += c;
      bins.pairs_per_part[part] += c;
    }
  }
  lanes_total = roundUpToPacket(offset);
  parallelSlices(threads, [&](int t, int) {
    auto& counts = bins.thread_counts[t];
    const auto [first, last] = sliceRange(ray_count, t, threads);
    for (size_t r = first; r < last; ++r) {
      // Copies: the pairs' stores could alias a reference's floats, so the compiler would
      // load every field again after each store.
      const GrRay ray = rays[r];
      const int octant = octantOf(ray);
      const int length = lists.lengthOf(r);
      const ListEntry* entries = lists.entriesOf(r);
      for (int e = 0; e < length; ++e) {
        const ListEntry entry = entries[e];
        writePair(out, counts[entry.pe * kOctants + octant]++, ray, int(r), entry);
      }
    }
  });
  bins.packets = size_t(lanes_total / GR_PACKET_LANES);
  bins.tasks.clear();
  bins.pairs_per_pe.assign(pe_count, 0);
  int start = 0;  // the part's first lane
  for (int part = 0; part < parts; ++part) {
    const int pe = part / kOctants, n = bins.pairs_per_part[part];
    if (n == 0) continue;
    bins.pairs_per_pe[pe] += n;
    for (int k = 0; k < n; k += task_rays)
      bins.tasks.push_back(
          GrPeTask{pe, (start + k) / GR_PACKET_LANES, std::min(task_rays, n - k), 0});
    // Zero the lanes past the part's last pair: no stale values in an inactive lane.
    for (int position = start + n; position % GR_PACKET_LANES != 0; ++position) {
      float* packet = out + size_t(position / GR_PACKET_LANES) * kPairPacketFloats;
      for (int q = 0; q < GR_PAIR_PLANES; ++q)
        packet[gr_pair_value(q, position % GR_PACKET_LANES)] = 0.0f;
    }
    start = roundUpToPacket(start + n);
  }
}

}  // namespace gridrt
