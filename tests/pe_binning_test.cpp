// Binning of traversal lists by PE (host/pe_binning.h): every (ray, PE) pair lands once in
// a task of its PE; a task's rays share their direction's octant and keep ray order.
#include <gtest/gtest.h>

#include <random>
#include <set>
#include <vector>

#include "pe_binning.h"

namespace {

using namespace gridrt;

int octant(const GrRay& r) { return (r.dx < 0) | (r.dy < 0) << 1 | (r.dz < 0) << 2; }

TEST(PeBinning, EveryPairOnceInATaskOfItsPeWithOneOctantInRayOrder) {
  const int pe_count = 5, task_rays = 4;
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  std::uniform_int_distribution<int> pick_pe(0, pe_count - 1), length(0, 4);
  std::vector<GrRay> rays(300);
  TraversalLists lists;
  lists.begin.push_back(0);
  for (GrRay& r : rays) {
    r = GrRay{0, 0, 0, 0, unit(rng), unit(rng), unit(rng), 1};
    std::set<int> pes;
    for (int k = length(rng); k > 0; --k) pes.insert(pick_pe(rng));
    for (int pe : pes) lists.entries.push_back(ListEntry{pe, float(pe), float(pe) + 0.5f});
    lists.begin.push_back(int(lists.entries.size()));
  }
  PeBins bins;
  binByPe(lists, rays.data(), pe_count, task_rays, bins);

  std::vector<int> seen(lists.entries.size(), 0), pairs(pe_count, 0);
  for (const GrPeTask& task : bins.tasks) {
    ASSERT_GE(task.entry_count, 1);
    ASSERT_LE(task.entry_count, task_rays);
    const GrPeEntry& head = bins.entries[task.first_entry];
    for (int k = 0; k < task.entry_count; ++k) {
      const GrPeEntry& e = bins.entries[task.first_entry + k];
      ASSERT_GE(e.slot, lists.begin[e.ray]);
      ASSERT_LT(e.slot, lists.begin[e.ray + 1]);
      EXPECT_EQ(lists.entries[e.slot].pe, task.pe) << "pair in another PE's task";
      EXPECT_EQ(e.t_enter, lists.entries[e.slot].t_enter);
      EXPECT_EQ(octant(rays[e.ray]), octant(rays[head.ray])) << "task mixes octants";
      if (k > 0) {
        EXPECT_LT(bins.entries[task.first_entry + k - 1].ray, e.ray) << "ray order";
      }
      ++seen[e.slot];
    }
    pairs[task.pe] += task.entry_count;
  }
  for (size_t s = 0; s < seen.size(); ++s) EXPECT_EQ(seen[s], 1) << "slot " << s;
  for (int pe = 0; pe < pe_count; ++pe) EXPECT_EQ(bins.pairs_per_pe[pe], pairs[pe]);
}

}  // namespace
