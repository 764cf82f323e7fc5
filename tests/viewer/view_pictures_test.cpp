// The views' pictures (view_pictures.h): tools/heatmap.py's colours, scaled as it scales
// them, and the image as its PNG holds it.
#include <gtest/gtest.h>

#include <set>

#include "eight_bit_image.h"
#include "view_pictures.h"

namespace gridrt {
namespace {

std::array<int, 3> colourOf(const Picture& p, size_t pixel) {
  return {p.rgb[3 * pixel], p.rgb[3 * pixel + 1], p.rgb[3 * pixel + 2]};
}

TEST(ViewPictures, ViridisRunsFromPurpleThroughTealToYellow) {
  unsigned char c[3];
  viridisColour(0.0f, c);
  EXPECT_EQ(std::vector<int>(c, c + 3), (std::vector<int>{68, 1, 84}));  // #440154
  viridisColour(0.5f, c);
  EXPECT_EQ(std::vector<int>(c, c + 3), (std::vector<int>{33, 145, 140}));  // #21918c
  viridisColour(1.0f, c);
  EXPECT_EQ(std::vector<int>(c, c + 3), (std::vector<int>{253, 231, 37}));  // #fde725
  viridisColour(7.0f, c);  // clamped
  EXPECT_EQ(c[0], 253);
  // Brighter all the way (viridis is perceptually ordered): green rises at every step.
  int green = -1;
  for (int k = 0; k <= 64; ++k) {
    viridisColour(float(k) / 64.0f, c);
    EXPECT_GT(int(c[1]), green) << k;
    green = c[1];
  }
}

TEST(ViewPictures, EveryPeGetsItsOwnBrightColourAndAMissIsBlack) {
  unsigned char c[3];
  peColour(-1, c);
  EXPECT_EQ(c[0] + c[1] + c[2], 0);
  std::set<std::array<int, 3>> seen;
  for (int pe = 0; pe < 500; ++pe) {
    peColour(pe, c);
    // heatmap.py's value (brightest channel) is at least 0.70.
    EXPECT_GE(std::max({c[0], c[1], c[2]}), 178) << pe;
    seen.insert({c[0], c[1], c[2]});
    unsigned char again[3];
    peColour(pe, again);
    EXPECT_EQ(std::vector<int>(c, c + 3), std::vector<int>(again, again + 3));
  }
  EXPECT_GE(seen.size(), 495u);  // neighbouring PEs told apart (a few 8-bit collisions)
}

TEST(ViewPictures, CountsAreScaledToTheLargest) {
  PrimaryAovs aovs;
  aovs.list_length = {0.0f, 1.0f, 2.0f, 4.0f};
  aovs.depth = {-1.0f, 1.0f, 2.5f, 4.0f};
  const Picture list = aovPicture(ViewKind::ListLength, aovs, 2, 2);
  unsigned char low[3], half[3], high[3];
  viridisColour(0.0f, low);
  viridisColour(0.5f, half);
  viridisColour(1.0f, high);
  EXPECT_EQ(colourOf(list, 0), (std::array<int, 3>{low[0], low[1], low[2]}));
  EXPECT_EQ(colourOf(list, 2), (std::array<int, 3>{half[0], half[1], half[2]}));
  EXPECT_EQ(colourOf(list, 3), (std::array<int, 3>{high[0], high[1], high[2]}));
  const Picture depth = aovPicture(ViewKind::Depth, aovs, 2, 2);
  EXPECT_EQ(colourOf(depth, 0), (std::array<int, 3>{0, 0, 0}));  // a miss
  // Depth from the nearest hit to the farthest.
  EXPECT_EQ(colourOf(depth, 1), (std::array<int, 3>{low[0], low[1], low[2]}));
  EXPECT_EQ(colourOf(depth, 2), (std::array<int, 3>{half[0], half[1], half[2]}));
  EXPECT_EQ(colourOf(depth, 3), (std::array<int, 3>{high[0], high[1], high[2]}));
}

TEST(ViewPictures, NormalsAndAlbedoAsColours) {
  PrimaryAovs aovs;
  aovs.shading_normal = {0, 0, 0, 1, 0, 0, 0, -1, 0, 0, 0, 1};
  aovs.albedo = {0, 0, 0, 1, 1, 1, 0.5f, 0.25f, 2.0f, 0, 0, 0};
  const Picture n = aovPicture(ViewKind::Normal, aovs, 4, 1);
  EXPECT_EQ(colourOf(n, 0), (std::array<int, 3>{0, 0, 0}));  // a miss
  EXPECT_EQ(colourOf(n, 1), (std::array<int, 3>{255, 128, 128}));
  EXPECT_EQ(colourOf(n, 2), (std::array<int, 3>{128, 0, 128}));
  const Picture a = aovPicture(ViewKind::Albedo, aovs, 4, 1);
  EXPECT_EQ(colourOf(a, 1), (std::array<int, 3>{255, 255, 255}));
  EXPECT_EQ(colourOf(a, 2), (std::array<int, 3>{linearToSrgb8(0.5f), linearToSrgb8(0.25f), 255}));
}

TEST(ViewPictures, TheImageIsItsPngCodes) {
  Film film;
  film.width = 2, film.height = 1;
  film.rgb = {0.0f, 0.5f, 1.0f, 0.2f, 7.0f, -1.0f};
  const Picture p = imagePicture(film);
  EXPECT_EQ(colourOf(p, 0), (std::array<int, 3>{0, linearToSrgb8(0.5f), 255}));
  EXPECT_EQ(colourOf(p, 1), (std::array<int, 3>{linearToSrgb8(0.2f), 255, 0}));
}

TEST(ViewPictures, ViewsCycleThroughAllAndNameTheirAov) {
  ViewKind k = ViewKind::Image;
  std::set<std::string> names;
  for (int i = 0; i < kViewKinds; ++i, k = nextView(k)) names.insert(viewName(k));
  EXPECT_EQ(k, ViewKind::Image);
  EXPECT_EQ(names, (std::set<std::string>{"image", "depth", "normal", "albedo", "pe", "tests",
                                          "listlen"}));
  EXPECT_TRUE(needsDiagnostics(ViewKind::Pe));
  EXPECT_TRUE(needsAovs(ViewKind::Depth));
  EXPECT_FALSE(needsAovs(ViewKind::Image) || needsDiagnostics(ViewKind::Image));
}

}  // namespace
}  // namespace gridrt
