// Binning of traversal lists by PE (host/gridrt/lists/pe_binning.h): every (ray, PE) pair lands
// once in a task of its PE; a task's rays share their direction's octant and keep ray order.
#include "pe_binning.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <random>
#include <set>
#include <vector>

namespace {

using namespace gridrt;

int octant(const GrRay& r) { return (r.dx < 0) | (r.dy < 0) << 1 | (r.dz < 0) << 2; }

TEST(PeBinning, EveryPairOnceInATaskOfItsPeWithOneOctantInRayOrder) {
  const int pe_count = 5, task_rays = 32;
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  std::uniform_int_distribution<int> pick_pe(0, pe_count - 1), length(0, 4);
  std::vector<GrRay> rays(5000);  // more than one chunk of lists (kListChunkRays)
  std::vector<int> begin{0};
  std::vector<ListEntry> entries;
  for (GrRay& r : rays) {
    r = GrRay{unit(rng), unit(rng), unit(rng), 0, unit(rng), unit(rng), unit(rng), 1};
    std::set<int> pes;
    for (int k = length(rng); k > 0; --k) pes.insert(pick_pe(rng));
    for (int pe : pes) entries.push_back(ListEntry{pe, float(pe), float(pe) + 0.5f});
    begin.push_back(int(entries.size()));
  }
  TraversalLists lists;
  lists.assign(begin, entries);
  PeBins bins;
  // A buffer with stale values, as the device buffer has from the batch before.
  std::vector<float> out(maxPairPackets(entries.size(), pe_count) * kPairPacketFloats, 7.0f);
  binByPe(lists, rays.data(), pe_count, task_rays, bins, out.data());

  // Lane k of packet p, plane q.
  auto plane = [&](int p, int q, int k) {
    return out[size_t(p) * kPairPacketFloats + size_t(gr_pair_value(q, k))];
  };
  auto planeBits = [&](int p, int q, int k) {
    float f = plane(p, q, k);
    int i;
    std::memcpy(&i, &f, sizeof i);
    return i;
  };
  auto planeInt = [&](int p, int q, int k) { return planeBits(p, q, k) & GR_PAIR_RAY_INDEX; };
  std::vector<int> seen(entries.size(), 0), pairs(pe_count, 0);
  std::vector<int> packet_used(bins.packets, 0);
  ASSERT_LE(bins.packets, maxPairPackets(entries.size(), pe_count));
  for (const GrPeTask& task : bins.tasks) {
    ASSERT_GE(task.pair_count, 1);
    ASSERT_LE(task.pair_count, task_rays);
    const int head_ray = planeInt(task.first_packet, GR_PAIR_RAY, 0);
    for (int k = 0; k < task.pair_count; ++k) {
      const int p = task.first_packet + k / GR_PACKET_LANES, lane = k % GR_PACKET_LANES;
      ASSERT_LT(size_t(p), bins.packets);
      ++packet_used[p];
      const int ray = planeInt(p, GR_PAIR_RAY, lane);
      ASSERT_GE(ray, 0);
      ASSERT_LT(size_t(ray), rays.size());
      // The pair's entry: a list holds each PE at most once.
      int slot = lists.begin[ray];
      while (slot < lists.begin[ray + 1] && entries[slot].pe != task.pe) ++slot;
      ASSERT_LT(slot, lists.begin[ray + 1]) << "pair in another PE's task";
      const GrRay& r = rays[ray];
      const ListEntry& entry = entries[slot];
      // The interval of the entry within the ray's, each end open where it is the ray's.
      const int bits = planeBits(p, GR_PAIR_RAY, lane);
      EXPECT_EQ(plane(p, GR_PAIR_T_LO, lane), std::max(r.tmin, entry.t_enter));
      EXPECT_EQ(plane(p, GR_PAIR_T_HI, lane), std::min(r.tmax, entry.t_exit));
      EXPECT_EQ((bits & GR_PAIR_LO_OPEN) != 0, r.tmin >= entry.t_enter);
      EXPECT_EQ((bits & GR_PAIR_HI_OPEN) != 0, r.tmax <= entry.t_exit);
      const float expected[] = {r.ox, r.oy, r.oz, r.dx, r.dy, r.dz};
      for (int q = GR_PAIR_OX; q <= GR_PAIR_DZ; ++q)
        EXPECT_EQ(plane(p, q, lane), expected[q]) << "the pair carries its ray";
      EXPECT_EQ(octant(rays[ray]), octant(rays[head_ray])) << "task mixes octants";
      if (k > 0) {
        const int before = k - 1;
        EXPECT_LT(planeInt(task.first_packet + before / GR_PACKET_LANES, GR_PAIR_RAY,
                           before % GR_PACKET_LANES),
                  ray)
            << "ray order";
      }
      ++seen[slot];
    }
    // The lanes past a task's last pair in its last packet are zero (no stale rays).
    if (task.pair_count % GR_PACKET_LANES != 0) {
      const int p = task.first_packet + task.pair_count / GR_PACKET_LANES;
      for (int lane = task.pair_count % GR_PACKET_LANES; lane < GR_PACKET_LANES; ++lane)
        for (int q = 0; q < GR_PAIR_PLANES; ++q) EXPECT_EQ(plane(p, q, lane), 0.0f);
    }
    pairs[task.pe] += task.pair_count;
  }
  for (size_t p = 0; p < packet_used.size(); ++p)
    EXPECT_LE(packet_used[p], GR_PACKET_LANES) << "two tasks share packet " << p;
  for (size_t s = 0; s < seen.size(); ++s) EXPECT_EQ(seen[s], 1) << "slot " << s;
  for (int pe = 0; pe < pe_count; ++pe) EXPECT_EQ(bins.pairs_per_pe[pe], pairs[pe]);
}

}  // namespace
