// merge_tiles OUT IN1 [IN2 ...]: pastes window-only tiles rendered with
//   gridrt --crop X0,Y0,X1,Y1 --crop-output window -o tile.exr
// into one image. Each tile says where it lies through its data window (OpenImageIO
// ImageSpec x, y inside full_width x full_height; EXR stores it natively, TIFF as position
// tags), so tiles can be given in any order. The tiles must agree on the full size and
// the channel count and must not overlap; pixels no tile covers are zero (with a warning).
// Values are copied as 32-bit floats, so merging is exact: the merged image equals a
// single full render bit for bit (tests/image/tiles_test.cpp). An OUT of .png, .jpg or
// .jpeg (three-channel tiles of a whole image) is encoded once, after the merge, by
// gridrt's own image writer, so it equals gridrt's 8-bit file too: encoding tiles first
// and pasting bytes would need a second encoder that must round exactly as gridrt does.
//
// Exit codes: 0 success, 2 usage, 1 unreadable, inconsistent or overlapping tiles.
#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <stdexcept>
#include <string>
#include <vector>

#include "errors.h"
#include "film.h"
#include "image_output.h"

namespace {

struct Tile {
  std::string path;
  OIIO::ImageSpec spec;       // x, y, width, height: the data window
  std::vector<float> pixels;  // width * height * nchannels, row-major
};

struct MergeError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

Tile readTile(const std::string& path) {
  auto in = OIIO::ImageInput::open(path);
  if (!in) throw MergeError("cannot read '" + path + "': " + OIIO::geterror());
  Tile t{path, in->spec(), {}};
  t.pixels.resize(size_t(t.spec.width) * t.spec.height * t.spec.nchannels);
  if (!in->read_image(0, 0, 0, t.spec.nchannels, OIIO::TypeDesc::FLOAT, t.pixels.data()))
    throw MergeError("cannot read '" + path + "': " + in->geterror());
  return t;
}

std::string windowText(const OIIO::ImageSpec& s) {
  return std::to_string(s.width) + "x" + std::to_string(s.height) + " at (" + std::to_string(s.x) +
         "," + std::to_string(s.y) + ")";
}

// The first tile fixes the full (display) window and the channels; the others must match,
// and every data window must lie inside the display window.
void checkConsistent(const Tile& first, const Tile& t) {
  const OIIO::ImageSpec &a = first.spec, &b = t.spec;
  if (b.full_x != a.full_x || b.full_y != a.full_y || b.full_width != a.full_width ||
      b.full_height != a.full_height)
    throw MergeError("'" + t.path + "' belongs to a " + std::to_string(b.full_width) + "x" +
                     std::to_string(b.full_height) + " image but '" + first.path + "' to a " +
                     std::to_string(a.full_width) + "x" + std::to_string(a.full_height) + " one");
  if (b.nchannels != a.nchannels)
    throw MergeError("'" + t.path + "' has " + std::to_string(b.nchannels) + " channels, '" +
                     first.path + "' " + std::to_string(a.nchannels));
  if (b.depth != 1 || b.z != 0)
    throw MergeError("'" + t.path + "' is a volume image; tiles must be flat");
  if (b.x < a.full_x || b.y < a.full_y || b.x + b.width > a.full_x + a.full_width ||
      b.y + b.height > a.full_y + a.full_height)
    throw MergeError("'" + t.path + "': its window " + windowText(b) +
                     " lies outside the full image");
}

// Pastes every tile into a full-size buffer; `owner` remembers which tile wrote a pixel,
// so an overlap is reported with both file names.
OIIO::ImageBuf paste(const std::vector<Tile>& tiles) {
  const OIIO::ImageSpec& f = tiles.front().spec;
  OIIO::ImageSpec spec(f.full_width, f.full_height, f.nchannels, OIIO::TypeDesc::FLOAT);
  spec.x = spec.full_x = f.full_x;
  spec.y = spec.full_y = f.full_y;
  spec.channelnames = f.channelnames;
  std::vector<float> out(size_t(spec.width) * spec.height * spec.nchannels, 0.0f);
  std::vector<int> owner(size_t(spec.width) * spec.height, -1);
  const size_t nc = size_t(spec.nchannels);
  for (size_t k = 0; k < tiles.size(); ++k) {
    const Tile& t = tiles[k];
    for (int row = 0; row < t.spec.height; ++row)
      for (int col = 0; col < t.spec.width; ++col) {
        size_t dst = size_t(t.spec.y - spec.y + row) * spec.width + (t.spec.x - spec.x + col);
        if (owner[dst] >= 0)
          throw MergeError("'" + t.path + "' and '" + tiles[owner[dst]].path +
                           "' overlap: each pixel must come from one tile (tiles written "
                           "with --crop-output full cover the whole image; use window)");
        owner[dst] = int(k);
        const float* src = t.pixels.data() + (size_t(row) * t.spec.width + col) * nc;
        std::copy(src, src + nc, out.begin() + dst * nc);
      }
  }
  size_t uncovered = 0;
  for (int o : owner) uncovered += o < 0;
  if (uncovered)
    std::cerr << "merge_tiles: warning: " << uncovered << " of " << owner.size()
              << " pixels are covered by no tile and are zero\n";
  OIIO::ImageBuf buf(spec);
  buf.set_pixels(buf.roi(), OIIO::TypeDesc::FLOAT, out.data());
  return buf;
}

// Written to a sibling temporary file and renamed, so a failure leaves no half image.
void writeMerged(const std::string& path, const OIIO::ImageBuf& buf) {
  namespace fs = std::filesystem;
  fs::path target(path), dir = target.parent_path().empty() ? "." : target.parent_path();
  fs::path temp = dir / ("." + target.stem().string() + ".merging" + target.extension().string());
  if (!buf.write(temp.string(), OIIO::TypeDesc::FLOAT)) {
    std::error_code ignored;
    fs::remove(temp, ignored);
    throw MergeError("cannot write '" + path + "': " + buf.geterror());
  }
  std::error_code ec;
  fs::rename(temp, target, ec);
  if (ec) throw MergeError("cannot write '" + path + "': " + ec.message());
}

std::string lowerExtension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

bool isFloatFormat(const std::string& path) {
  const std::string ext = lowerExtension(path);
  return ext == ".exr" || ext == ".tif" || ext == ".tiff";
}

bool isEightBitFormat(const std::string& path) {
  const std::string ext = lowerExtension(path);
  return ext == ".png" || ext == ".jpg" || ext == ".jpeg";
}

// An 8-bit image is a rendered picture: RGB tiles of an image whose display window starts
// at the origin, written through gridrt's writeImage (sRGB-encoded as gridrt encodes).
void writeEightBit(const std::string& path, const OIIO::ImageBuf& merged) {
  const OIIO::ImageSpec& spec = merged.spec();
  if (spec.nchannels != 3)
    throw MergeError("a .png or .jpg needs RGB tiles; these have " +
                     std::to_string(spec.nchannels) + " channels (write .exr)");
  if (spec.full_x != 0 || spec.full_y != 0)
    throw MergeError("a .png or .jpg needs tiles of an image whose display window starts at 0,0");
  gridrt::Film film;
  film.width = spec.width;
  film.height = spec.height;
  film.rgb.resize(size_t(film.width) * film.height * 3);
  merged.get_pixels(merged.roi(), OIIO::TypeDesc::FLOAT, film.rgb.data());
  try {
    gridrt::writeImage(path, film);
  } catch (const gridrt::RenderError& e) {
    throw MergeError(e.what());
  }
}

}  // namespace

int main(int argc, char** argv) {
  const char* usage =
      "usage: merge_tiles OUT.exr TILE1.exr [TILE2.exr ...]\n"
      "  pastes tiles written by 'gridrt --crop X0,Y0,X1,Y1 --crop-output window';\n"
      "  OUT may be .exr/.tif/.tiff (floats, exact) or .png/.jpg (encoded as gridrt does)\n";
  if (argc == 2 && (std::string(argv[1]) == "--help" || std::string(argv[1]) == "-h")) {
    std::cout << usage;
    return 0;
  }
  if (argc < 3) {
    std::cerr << usage;
    return 2;
  }
  const std::string out = argv[1];
  // Floats are kept exactly; 8-bit files are encoded once, after the merge, by gridrt's writer.
  if (!isFloatFormat(out) && !isEightBitFormat(out)) {
    std::cerr << "merge_tiles: the output must be .exr, .tif, .tiff, .png, .jpg or .jpeg, got '"
              << out << "'\n";
    return 2;
  }
  try {
    std::vector<Tile> tiles;
    for (int i = 2; i < argc; ++i) {
      tiles.push_back(readTile(argv[i]));
      checkConsistent(tiles.front(), tiles.back());
    }
    const OIIO::ImageBuf merged = paste(tiles);
    if (isEightBitFormat(out))
      writeEightBit(out, merged);
    else
      writeMerged(out, merged);
  } catch (const MergeError& e) {
    std::cerr << "merge_tiles: " << e.what() << '\n';
    return 1;
  }
  return 0;
}
