// Tiled rendering: tiles rendered with `gridrt --crop ... --crop-output window` and pasted
// by gridrt-merge-tiles equal one full render bit for bit, and each tile file carries its
// offset in its data window. Runs gridrt and gridrt-merge-tiles as subprocesses.
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "image_output.h"
#include "run_command.h"
#include "test_support.h"

namespace {

using gridrt::test::CommandResult;
using gridrt::test::gridrtBinary;
using gridrt::test::joinArgs;
using gridrt::test::runCommand;
using gridrt::test::tempPath;

// gridrt-merge-tiles is built next to gridrt, in the tools/ folder of the build.
std::string mergeTilesBinary() {
  const std::filesystem::path tools = std::filesystem::path(gridrtBinary()).parent_path() / "tools";
  return (tools / "gridrt-merge-tiles").string();
}

void expectSuccess(const std::vector<std::string>& argv) {
  CommandResult r = runCommand(argv);
  ASSERT_EQ(r.exit_code, 0) << joinArgs(argv) << "\n" << r.err;
}

// Renders the default scene at 64x48 with `extra` flags to `path`.
void render(const std::string& path, std::vector<std::string> extra) {
  std::vector<std::string> argv{gridrtBinary(), "-q", "--width", "64",
                                "--height",     "48", "-o",      path};
  argv.insert(argv.end(), extra.begin(), extra.end());
  expectSuccess(argv);
}

struct Rect {
  int x0, y0, x1, y1;
  std::string text() const {
    return std::to_string(x0) + "," + std::to_string(y0) + "," + std::to_string(x1) + "," +
           std::to_string(y1);
  }
};

// A window file's data window: the window's offset and size, in an image of full size.
void expectDataWindow(const OIIO::ImageSpec& s, int x, int y, int width, int height, int full_width,
                      int full_height) {
  EXPECT_EQ(s.x, x);
  EXPECT_EQ(s.y, y);
  EXPECT_EQ(s.width, width);
  EXPECT_EQ(s.height, height);
  EXPECT_EQ(s.full_width, full_width);
  EXPECT_EQ(s.full_height, full_height);
}

// Renders `tiles`, merges them, and compares with one full render, bit for bit.
void expectTilesMergeToFullRender(const std::string& name, const std::vector<Rect>& tiles,
                                  const std::vector<std::string>& flags) {
  if (!std::filesystem::exists(mergeTilesBinary()))
    GTEST_SKIP() << "gridrt-merge-tiles is not built at " << mergeTilesBinary();
  const std::string full = tempPath(name + "_full.exr"), merged = tempPath(name + "_merged.exr");
  render(full, flags);
  std::vector<std::string> merge{mergeTilesBinary(), merged};
  for (size_t k = 0; k < tiles.size(); ++k) {
    std::string tile = tempPath(name + "_tile" + std::to_string(k) + ".exr");
    std::vector<std::string> tile_flags = flags;
    tile_flags.insert(tile_flags.end(), {"--crop", tiles[k].text(), "--crop-output", "window"});
    render(tile, tile_flags);
    merge.push_back(tile);
  }
  expectSuccess(merge);
  gridrt::ImageData a = gridrt::readImage(full), b = gridrt::readImage(merged);
  ASSERT_EQ(a.width, b.width);
  ASSERT_EQ(a.height, b.height);
  ASSERT_EQ(a.channels, b.channels);
  ASSERT_EQ(a.pixels.size(), b.pixels.size());
  EXPECT_EQ(std::memcmp(a.pixels.data(), b.pixels.data(), a.pixels.size() * sizeof(float)), 0)
      << "merged tiles differ from the full render";
}

TEST(Tiles, FourTilesMergeToTheFullRenderBitForBit) {
  expectTilesMergeToFullRender(
      "even", {{0, 0, 32, 24}, {32, 0, 64, 24}, {0, 24, 32, 48}, {32, 24, 64, 48}}, {});
}

// Uneven bounds and jittered samples: the jitter must follow the full image's pixel index.
TEST(Tiles, UnevenTilesWithSeveralSamplesMergeBitForBit) {
  expectTilesMergeToFullRender("jitter",
                               {{0, 0, 23, 17}, {23, 0, 64, 17}, {0, 17, 23, 48}, {23, 17, 64, 48}},
                               {"--spp", "3"});
}

// Adaptive AA refines a pixel where a 4-neighbour's centre differs: a pixel on a tile's
// edge must see its neighbours in the next tile, as it does in the full render. Tiles one
// row and one column wide (every pixel on an edge) and a seam through the scene's edges.
TEST(Tiles, AdaptiveAntiAliasingTilesMergeBitForBit) {
  expectTilesMergeToFullRender("adaptive",
                               {{0, 0, 31, 23},
                                {31, 0, 64, 23},
                                {0, 23, 31, 24},
                                {31, 23, 64, 24},
                                {0, 24, 30, 48},
                                {30, 24, 31, 48},
                                {31, 24, 64, 48}},
                               {"--aa", "adaptive", "--aa-samples", "3"});
}

// --spp beside --aa adaptive (which takes its samples from --aa-samples) on the even tiles
// whose seam the scene's edges cross: before the renderer traced the ring of neighbours
// around a window, 18 pixels on this seam differed from the full render.
TEST(Tiles, AdaptiveAntiAliasingWithSamplesPerPixelMergeBitForBit) {
  expectTilesMergeToFullRender("adaptive_spp",
                               {{0, 0, 32, 24}, {32, 0, 64, 24}, {0, 24, 32, 48}, {32, 24, 64, 48}},
                               {"--aa", "adaptive", "--spp", "4"});
}

// The AOVs of an adaptive tile are the full render's in the window (the ring of
// neighbours the renderer traces around it is cut from them as from the image).
TEST(Tiles, AdaptiveAntiAliasingTileAovsAreTheFullRendersInTheWindow) {
  const Rect tile{10, 5, 41, 30};
  const std::string full = tempPath("aov_full.exr"), full_depth = tempPath("aov_full_depth.exr"),
                    full_normal = tempPath("aov_full_normal.exr");
  const std::string part = tempPath("aov_tile.exr"), part_depth = tempPath("aov_tile_depth.exr"),
                    part_normal = tempPath("aov_tile_normal.exr");
  render(full,
         {"--aa", "adaptive", "--aov", "depth=" + full_depth, "--aov", "normal=" + full_normal});
  render(part, {"--aa", "adaptive", "--crop", tile.text(), "--crop-output", "window", "--aov",
                "depth=" + part_depth, "--aov", "normal=" + part_normal});
  for (const auto& [whole, window] : {std::pair{full, part}, std::pair{full_depth, part_depth},
                                      std::pair{full_normal, part_normal}}) {
    gridrt::ImageData a = gridrt::readImage(whole), b = gridrt::readImage(window);
    ASSERT_EQ(b.width, tile.x1 - tile.x0) << window;
    ASSERT_EQ(b.height, tile.y1 - tile.y0) << window;
    ASSERT_EQ(a.channels, b.channels) << window;
    size_t differ = 0;
    for (int y = tile.y0; y < tile.y1; ++y)
      for (int x = tile.x0; x < tile.x1; ++x)
        for (int c = 0; c < a.channels; ++c)
          differ += a.pixels[(size_t(y) * a.width + x) * a.channels + c] !=
                    b.pixels[(size_t(y - tile.y0) * b.width + (x - tile.x0)) * b.channels + c];
    EXPECT_EQ(differ, 0u) << window << " differs from " << whole << " in the window";
  }
}

TEST(Tiles, WindowFileCarriesItsOffsetInTheDataWindow) {
  const std::string tile = tempPath("offset.exr");
  render(tile, {"--crop", "10,5,30,25", "--crop-output", "window"});
  auto in = OIIO::ImageInput::open(tile);
  ASSERT_TRUE(in) << OIIO::geterror();
  expectDataWindow(in->spec(), 10, 5, 20, 20, 64, 48);
}

TEST(Tiles, FullOutputIsZeroOutsideTheWindowAndTheRenderInside) {
  const std::string full = tempPath("ref.exr"), cropped = tempPath("cropped_full.exr");
  render(full, {});
  render(cropped, {"--crop", "8,4,40,30"});
  gridrt::ImageData a = gridrt::readImage(full), b = gridrt::readImage(cropped);
  ASSERT_EQ(b.width, 64);
  ASSERT_EQ(b.height, 48);
  for (int y = 0; y < 48; ++y)
    for (int x = 0; x < 64; ++x)
      for (int c = 0; c < 3; ++c) {
        size_t i = (size_t(y) * 64 + x) * 3 + c;
        bool inside = x >= 8 && x < 40 && y >= 4 && y < 30;
        ASSERT_EQ(b.pixels[i], inside ? a.pixels[i] : 0.0f) << "pixel " << x << "," << y;
      }
}

std::string fileBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// An 8-bit OUT is encoded once, after the merge, by gridrt's own writer: the merged PNG is
// gridrt's PNG of the full render byte for byte (uneven tiles, jittered samples, so tiles
// would round differently if each were encoded on its own with another encoder).
TEST(Tiles, MergedPngIsTheFullRendersPngByteForByte) {
  if (!std::filesystem::exists(mergeTilesBinary()))
    GTEST_SKIP() << "gridrt-merge-tiles is not built at " << mergeTilesBinary();
  const std::vector<Rect> tiles{{0, 0, 23, 17}, {23, 0, 64, 17}, {0, 17, 23, 48}, {23, 17, 64, 48}};
  const std::string full = tempPath("png_full.png"), merged = tempPath("png_merged.png");
  render(full, {"--spp", "3"});
  std::vector<std::string> merge{mergeTilesBinary(), merged};
  for (size_t k = 0; k < tiles.size(); ++k) {
    std::string tile = tempPath("png_tile" + std::to_string(k) + ".exr");
    render(tile, {"--spp", "3", "--crop", tiles[k].text(), "--crop-output", "window"});
    merge.push_back(tile);
  }
  expectSuccess(merge);
  const std::string a = fileBytes(full), b = fileBytes(merged);
  ASSERT_GT(a.size(), 100u);
  EXPECT_TRUE(a == b) << "merged PNG (" << b.size() << " bytes) differs from gridrt's (" << a.size()
                      << " bytes)";
}

// With --alpha the tiles hold premultiplied colour and the background: the merged PNG's
// unassociated colour and alpha are the full render's byte for byte (the bunny, with the
// background around it and partly covered edge pixels).
TEST(Tiles, MergedPngWithAlphaIsTheFullRendersPngByteForByte) {
  if (!std::filesystem::exists(mergeTilesBinary()))
    GTEST_SKIP() << "gridrt-merge-tiles is not built at " << mergeTilesBinary();
  const std::vector<Rect> tiles{{0, 0, 23, 17}, {23, 0, 64, 17}, {0, 17, 23, 48}, {23, 17, 64, 48}};
  const std::vector<std::string> flags{gridrt::test::modelScene("bunny_res4.glb"),
                                       "--spp",
                                       "3",
                                       "--alpha",
                                       "--background",
                                       "0.2,0.4,0.6"};
  const std::string full = tempPath("alpha_full.png"), merged = tempPath("alpha_merged.png");
  render(full, flags);
  std::vector<std::string> merge{mergeTilesBinary(), merged};
  for (size_t k = 0; k < tiles.size(); ++k) {
    std::string tile = tempPath("alpha_tile" + std::to_string(k) + ".exr");
    std::vector<std::string> tile_flags = flags;
    tile_flags.insert(tile_flags.end(), {"--crop", tiles[k].text(), "--crop-output", "window"});
    render(tile, tile_flags);
    merge.push_back(tile);
  }
  expectSuccess(merge);
  EXPECT_EQ(gridrt::readImage(full).channels, 4);
  const std::string a = fileBytes(full), b = fileBytes(merged);
  ASSERT_GT(a.size(), 100u);
  EXPECT_TRUE(a == b) << "merged PNG (" << b.size() << " bytes) differs from gridrt's (" << a.size()
                      << " bytes)";
}

// A one-channel AOV has no colours to encode: an 8-bit OUT is refused, nothing written.
TEST(Tiles, EightBitOutputOfNonRgbTilesIsRefused) {
  if (!std::filesystem::exists(mergeTilesBinary()))
    GTEST_SKIP() << "gridrt-merge-tiles is not built at " << mergeTilesBinary();
  const std::string tile = tempPath("aov_tile_image.exr"), depth = tempPath("aov_tile_depth.exr");
  render(tile, {"--crop", "0,0,64,48", "--crop-output", "window", "--aov", "depth=" + depth});
  const std::string merged = tempPath("aov_merged.png");
  CommandResult r = runCommand({mergeTilesBinary(), merged, depth});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("needs float channels R, G and B"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(merged));
}

TEST(Tiles, OverlappingTilesAreRefused) {
  if (!std::filesystem::exists(mergeTilesBinary()))
    GTEST_SKIP() << "gridrt-merge-tiles is not built at " << mergeTilesBinary();
  const std::string a = tempPath("overlap_a.exr"), b = tempPath("overlap_b.exr");
  render(a, {"--crop", "0,0,32,24", "--crop-output", "window"});
  render(b, {"--crop", "16,0,48,24", "--crop-output", "window"});
  const std::string merged = tempPath("overlap_merged.exr");
  CommandResult r = runCommand({mergeTilesBinary(), merged, a, b});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("overlap"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(merged));
}

// The film holds the window alone, so a tile of an image far too large for memory renders
// in the memory of the tile: a 64x40 window of a 65536x65536 image (4.3 gigapixels,
// ~400 GiB at full size) is written with its offset, while the same window written at full
// size is refused before anything is rendered, with the window named.
TEST(Tiles, ATileOfAnImageTooLargeForMemoryRenders) {
  const std::string tile = tempPath("huge_tile.exr");
  expectSuccess({gridrtBinary(), "-q", "--width", "65536", "--height", "65536", "--crop",
                 "30000,30000,30064,30040", "--crop-output", "window", "-o", tile});
  auto in = OIIO::ImageInput::open(tile);
  ASSERT_TRUE(in) << OIIO::geterror();
  const OIIO::ImageSpec& s = in->spec();
  expectDataWindow(s, 30000, 30000, 64, 40, 65536, 65536);
  std::vector<float> pixels(size_t(s.width) * s.height * s.nchannels);
  ASSERT_TRUE(in->read_image(0, 0, 0, s.nchannels, OIIO::TypeDesc::FLOAT, pixels.data()));
  size_t lit = 0;
  for (float v : pixels) lit += v > 0.0f;
  EXPECT_GT(lit, pixels.size() / 2);  // the middle of the default scene: its back wall
  CommandResult r =
      runCommand({gridrtBinary(), "-q", "--width", "65536", "--height", "65536", "--crop",
                  "30000,30000,30064,30040", "-o", tempPath("huge_full.exr")});
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.err.find("window 30000,30000,30064,30040, written full size"), std::string::npos)
      << r.err;
}

}  // namespace
