#include "traversal_lists.h"

#include <algorithm>

#include "adaptive_lists.h"
#include "dda_packet.h"
#include "parallel_loops.h"
#include "parallel_scan.h"

namespace gridrt {

void TraversalLists::assign(const std::vector<int>& flat_begin,
                            const std::vector<ListEntry>& flat) {
  begin = flat_begin;
  const size_t rays = rayCount(), count = (rays + kListChunkRays - 1) / kListChunkRays;
  if (chunks.size() < count) chunks.resize(count);
  for (size_t c = 0; c < count; ++c) {
    const size_t first = c * kListChunkRays, last = std::min(rays, first + kListChunkRays);
    chunks[c].assign(flat.begin() + begin[first], flat.begin() + begin[last]);
  }
}

void computeListsOverCells(const GrGridInfo& g, const int* codes, const GrRay* rays, size_t count,
                           TraversalLists& lists, const ExpandCells& expand) {
  // Chunks handed out dynamically (list lengths vary a lot across a batch), each with its
  // own output (TraversalLists::chunks).
  const size_t chunks = (count + kListChunkRays - 1) / kListChunkRays;
  if (lists.chunks.size() < chunks) lists.chunks.resize(chunks);
  lists.begin.resize(count + 1);
  lists.begin[0] = 0;
  // Lane-major room for a packet's cells: a ray visits fewer than nx + ny + nz voxels.
  const int stride = g.nx + g.ny + g.nz;
  const int lanes = ddaPacketLanes();
  lists.packet_scratch.resize(threadSlotCount());
  for (auto& s : lists.packet_scratch) s.resize(lanes * size_t(stride));
  parallelForDynamic(0LL, (long long)(chunks), 1LL, [&](long long chunk) {
    auto& out = lists.chunks[chunk];
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
  // The counts made offsets (begin[0] is 0).
  inclusiveScan(lists.begin.data() + 1, count);
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
