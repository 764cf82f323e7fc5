// --crop X0,Y0,X1,Y1: a rectangular window of the image: the half-open pixel
// range [x0, x1) x [y0, y1), columns from the left, rows from the top, in the coordinates
// of the full image. Rendering tiles with it and pasting them (gridrt-merge-tiles) gives
// the full render bit for bit, because each pixel's rays do not depend on the window.
//
// The window itself is the Renderer's PixelWindow (RenderSettings::crop traces only its
// rays, and its film holds the window's pixels alone); this file parses it and places a
// rendered window in the full image.
#pragma once
#include <algorithm>
#include <string>
#include <vector>

#include "pixel_window.h"

namespace gridrt {

// What --crop writes: the full-size image with zeros outside the window, or the window
// alone, carrying its offset in the file's data window (EXR/TIFF).
enum class CropOutput { Full, Window };

// Parses "X0,Y0,X1,Y1" and checks 0 <= X0 < X1 <= width and 0 <= Y0 < Y1 <= height.
// Throws UsageError naming the flag and the problem.
PixelWindow parseCropWindow(const std::string& text, int width, int height);

// The window's pixels (row-major, window.width() x window.height() pixels of `channels`
// interleaved values, as the renderer's film holds them) placed in a width x height image,
// `outside` outside the window (the AOV's miss value: -1 for ids and depth, else 0).
template <typename T>
std::vector<T> placeWindow(const std::vector<T>& window_data, int width, int height, int channels,
                           const PixelWindow& window, T outside = T()) {
  std::vector<T> out(size_t(width) * height * channels, outside);
  const size_t row = size_t(window.width()) * channels;
  for (int y = window.y0; y < window.y1; ++y)
    std::copy_n(window_data.begin() + size_t(y - window.y0) * row, row,
                out.begin() + (size_t(y) * width + window.x0) * channels);
  return out;
}

}  // namespace gridrt
