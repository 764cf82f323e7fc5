#include "traversal_lists.h"

#include <algorithm>
#include <cstring>

#include "adaptive_lists.h"
#include "dda_packet.h"
#include "parallel_loops.h"

namespace gridrt {

namespace {

// The last step of building lists chunk by chunk (kListChunkRays rays each, on all cores):
// lists.begin[r + 1] holds ray r's entry count and lists.scratch[c] chunk c's entries;
// turns the counts into offsets and copies the chunks, in order, into lists.entries.
void gatherChunkLists(TraversalLists& lists, size_t count, size_t chunks) {
  for (size_t r = 0; r < count; ++r) lists.begin[r + 1] += lists.begin[r];
  lists.entries.resize(lists.begin[count]);
  parallelFor(0LL, (long long)(chunks), [&](long long chunk) {
    const auto& out = lists.scratch[chunk];
    if (!out.empty())
      std::memcpy(&lists.entries[lists.begin[size_t(chunk) * kListChunkRays]], out.data(),
                  out.size() * sizeof(ListEntry));
  });
}

}  // namespace

void computeListsOverCells(const GrGridInfo& g, const int* codes, const GrRay* rays, size_t count,
                           TraversalLists& lists, const ExpandCells& expand) {
  // Chunks handed out dynamically (list lengths vary a lot across a batch), each with its
  // own output, copied out in chunk order.
  const size_t chunks = (count + kListChunkRays - 1) / kListChunkRays;
  if (lists.scratch.size() < chunks) lists.scratch.resize(chunks);
  lists.begin.resize(count + 1);
  lists.begin[0] = 0;
  // Lane-major room for a packet's cells: a ray visits fewer than nx + ny + nz voxels.
  const int stride = g.nx + g.ny + g.nz;
  const int lanes = ddaPacketLanes();
  lists.packet_scratch.resize(threadSlotCount());
  for (auto& s : lists.packet_scratch) s.resize(lanes * size_t(stride));
  parallelForDynamic(0LL, (long long)(chunks), 1LL, [&](long long chunk) {
    auto& out = lists.scratch[chunk];
    out.clear();
    const size_t first = size_t(chunk) * kListChunkRays;
    const size_t last = std::min(count, first + kListChunkRays);
    ListEntry* packet = lists.packet_scratch[currentThreadSlot()].data();
    int found[kDdaPacketMaxLanes];
    for (size_t r = first; r < last; r += lanes) {
      const int n = int(std::min<size_t>(lanes, last - r));
      ddaPacket(g, codes, rays + r, n, packet, stride, found);
      for (int k = 0; k < n; ++k) {
        const size_t before = out.size();
        if (found[k] > 0) expand(rays[r + k], packet + size_t(k) * stride, found[k], out);
        lists.begin[r + k + 1] = int(out.size() - before);  // a count for now
      }
    }
  });
  gatherChunkLists(lists, count, chunks);
}

void computeTraversalLists(const UniformGrid& grid, const GrRay* rays, size_t count,
                           TraversalLists& lists) {
  if (!grid.adaptive.empty()) {
    computeAdaptiveLists(grid, rays, count, lists);
    return;
  }
  computeListsOverCells(
      grid.info, grid.pe_of_voxel.data(), rays, count, lists,
      [](const GrRay&, const ListEntry* cells, int n, std::vector<ListEntry>& out) {
        out.insert(out.end(), cells, cells + n);
      });
}

}  // namespace gridrt
