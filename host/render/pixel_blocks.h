// The order the primary generation is shaded in: 4x4 blocks of pixels. Shading spawns the
// next generation's rays in this order, and the PEs take their rays 16 at a time in ray
// order (pe_binning.h), so a packet of reflection, refraction or shadow rays comes from a
// compact block of pixels rather than a strip of one row: its rays start close together
// and point alike, and segment culling (segment_culling.h) skips more triangles for it.
#pragma once
#include <vector>

namespace gridrt {

// Edge of the square blocks, in pixels: a block is one 16-lane packet.
constexpr int kPixelBlockEdge = 4;

// The row-major indices of a width x height window (index y * width + x), listed block by
// block (blocks row-major, clipped at the window's right and bottom edges), each block's
// pixels row-major: a permutation of 0 .. width * height - 1.
void pixelBlockOrder(int width, int height, std::vector<int>& order);

}  // namespace gridrt
