// A window of pixels [x0, x1) x [y0, y1); an empty window (x1 == 0, y1 == 0) means the
// whole image.
#pragma once

namespace gridrt {

struct PixelWindow {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  bool whole() const { return x1 == 0 && y1 == 0; }
  int width() const { return x1 - x0; }
  int height() const { return y1 - y0; }
  // The pixels this window names in a width x height image: itself, or the whole image.
  PixelWindow orWholeImage(int width, int height) const {
    return whole() ? PixelWindow{0, 0, width, height} : *this;
  }
  bool operator==(const PixelWindow& o) const {
    return x0 == o.x0 && y0 == o.y0 && x1 == o.x1 && y1 == o.y1;
  }
  bool operator!=(const PixelWindow& o) const { return !(*this == o); }
};

}  // namespace gridrt
