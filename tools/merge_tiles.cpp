// gridrt-merge-tiles OUT IN1 [IN2 ...]: pastes window-only tiles rendered with
//   gridrt --crop X0,Y0,X1,Y1 --crop-output window -o tile.exr
// into one image. Each tile says where it lies through its data window (OpenImageIO
// ImageSpec x, y inside full_width x full_height; EXR stores it natively, TIFF as position
// tags), so tiles can be given in any order. The tiles must agree on the full size and
// the channels and must not overlap; pixels no tile covers are zero (with a warning).
// Values are copied as they are stored (32-bit floats and unsigned integers), and the
// merged image is written by gridrt's own image writer, so merging is exact: the merged
// file equals a single full render's bit for bit (tests/image/tiles_test.cpp). An OUT of
// .png, .jpg or .jpeg (tiles of a whole image) is encoded once, after the merge, so it
// equals gridrt's 8-bit file too: encoding tiles first and pasting bytes would need a
// second encoder that must round exactly as gridrt does.
//
// Exit codes: 0 success, 2 usage, 1 unreadable, inconsistent or overlapping tiles.
#include <iostream>
#include <stdexcept>
#include <string>
#include <vector>

#include "errors.h"
#include "image_output.h"

namespace {

using gridrt::ImageChannel;
using gridrt::LayeredImage;
using gridrt::SampleType;

struct Tile {
  std::string path;
  LayeredImage image;  // x, y, width, height: the data window
};

struct MergeError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

Tile readTile(const std::string& path) {
  try {
    return Tile{path, gridrt::readLayeredImage(path)};
  } catch (const gridrt::RenderError& e) {
    throw MergeError(e.what());
  }
}

std::string windowText(const LayeredImage& s) {
  return std::to_string(s.width) + "x" + std::to_string(s.height) + " at (" + std::to_string(s.x) +
         "," + std::to_string(s.y) + ")";
}

std::string channelsText(const LayeredImage& s) {
  std::string text;
  for (const ImageChannel& c : s.channels)
    text += (text.empty() ? "" : ",") + c.name + (c.type == SampleType::UInt ? " (uint)" : "");
  return text;
}

// The first tile fixes the full (display) window and the channels; the others must match,
// and every data window must lie inside the display window.
void checkConsistent(const Tile& first, const Tile& t) {
  const LayeredImage &a = first.image, &b = t.image;
  if (b.full_width != a.full_width || b.full_height != a.full_height)
    throw MergeError("'" + t.path + "' belongs to a " + std::to_string(b.full_width) + "x" +
                     std::to_string(b.full_height) + " image but '" + first.path + "' to a " +
                     std::to_string(a.full_width) + "x" + std::to_string(a.full_height) + " one");
  if (channelsText(a) != channelsText(b))
    throw MergeError("'" + t.path + "' has the channels " + channelsText(b) + ", '" + first.path +
                     "' " + channelsText(a));
  if (b.x < 0 || b.y < 0 || b.x + b.width > a.full_width || b.y + b.height > a.full_height)
    throw MergeError("'" + t.path + "': its window " + windowText(b) +
                     " lies outside the full image");
}

// Pastes every tile into a full-size image; `owner` remembers which tile wrote a pixel,
// so an overlap is reported with both file names.
LayeredImage paste(const std::vector<Tile>& tiles) {
  const LayeredImage& f = tiles.front().image;
  LayeredImage out;
  out.width = out.full_width = f.full_width;
  out.height = out.full_height = f.full_height;
  out.background = f.background;
  const size_t pixels = size_t(out.width) * out.height;
  for (const ImageChannel& c : f.channels) {
    out.channels.push_back(ImageChannel{c.name, c.type, {}, {}});
    if (c.type == SampleType::Float)
      out.channels.back().floats.assign(pixels, 0.0f);
    else
      out.channels.back().uints.assign(pixels, 0u);
  }
  std::vector<int> owner(pixels, -1);
  for (size_t k = 0; k < tiles.size(); ++k) {
    const LayeredImage& t = tiles[k].image;
    for (int row = 0; row < t.height; ++row)
      for (int col = 0; col < t.width; ++col) {
        const size_t dst = size_t(t.y + row) * out.width + size_t(t.x + col);
        const size_t src = size_t(row) * t.width + col;
        if (owner[dst] >= 0)
          throw MergeError("'" + tiles[k].path + "' and '" + tiles[owner[dst]].path +
                           "' overlap: each pixel must come from one tile (tiles written "
                           "with --crop-output full cover the whole image; use window)");
        owner[dst] = int(k);
        for (size_t c = 0; c < out.channels.size(); ++c) {
          ImageChannel& to = out.channels[c];
          if (to.type == SampleType::Float)
            to.floats[dst] = t.channels[c].floats[src];
          else
            to.uints[dst] = t.channels[c].uints[src];
        }
      }
  }
  size_t uncovered = 0;
  for (int o : owner) uncovered += o < 0;
  if (uncovered)
    std::cerr << "gridrt-merge-tiles: warning: " << uncovered << " of " << owner.size()
              << " pixels are covered by no tile and are zero\n";
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  const char* usage =
      "usage: gridrt-merge-tiles OUT.exr TILE1.exr [TILE2.exr ...]\n"
      "  pastes tiles written by 'gridrt --crop X0,Y0,X1,Y1 --crop-output window';\n"
      "  OUT may be .exr/.tif/.tiff (exact) or .png/.jpg (encoded as gridrt does)\n";
  if (argc == 2 && (std::string(argv[1]) == "--help" || std::string(argv[1]) == "-h")) {
    std::cout << usage;
    return 0;
  }
  if (argc < 3) {
    std::cerr << usage;
    return 2;
  }
  const std::string out = argv[1];
  const std::optional<gridrt::ImageFormat> format = gridrt::formatOfPath(out);
  if (!format || *format == gridrt::ImageFormat::Hdr) {
    std::cerr << "gridrt-merge-tiles: the output must be .exr, .tif, .tiff, .png, .jpg or .jpeg, got '"
              << out << "'\n";
    return 2;
  }
  try {
    std::vector<Tile> tiles;
    for (int i = 2; i < argc; ++i) {
      tiles.push_back(readTile(argv[i]));
      checkConsistent(tiles.front(), tiles.back());
    }
    // Written as gridrt writes its image: 8-bit files from the colour (and alpha).
    gridrt::writeLayeredImage(out, paste(tiles), gridrt::OutputKind::Image);
  } catch (const MergeError& e) {
    std::cerr << "gridrt-merge-tiles: " << e.what() << '\n';
    return 1;
  } catch (const gridrt::RenderError& e) {
    std::cerr << "gridrt-merge-tiles: " << e.what() << '\n';
    return 1;
  }
  return 0;
}
