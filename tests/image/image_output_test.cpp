// Image writing and reading: sRGB encoding of 8-bit output, exact float EXR and AOVs,
// one-line errors naming the file, and atomic writes (no half-written or temporary files).
#include "image_output.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "errors.h"
#include "test_support.h"

namespace fs = std::filesystem;
using gridrt::Film;
using gridrt::ImageData;
using gridrt::RenderError;

namespace {

// Fresh per-test directories: test_support.h.
std::string freshDir(const std::string& name) {
  return gridrt::test::freshDir("image_output_" + name);
}
using gridrt::test::listDir;

std::string fileBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

// A film of linear RGB values without alpha.
Film rgbFilm(int width, int height, std::vector<float> rgb) {
  Film film;
  film.width = width;
  film.height = height;
  film.rgb = std::move(rgb);
  return film;
}

// Runs `write`, expects a RenderError and returns its message.
template <class F>
std::string renderErrorOf(F write) {
  try {
    write();
  } catch (const RenderError& e) {
    return e.what();
  }
  ADD_FAILURE() << "expected a RenderError";
  return "";
}

}  // namespace

TEST(ImageOutput, PngRoundTripAppliesSrgbEncodingAndClamps) {
  const std::string path = freshDir("png") + "/out.png";
  // Pixels: (0.5, 0, 1) and (2, -1, NaN): out-of-range values clamp, NaN becomes black.
  Film film = rgbFilm(2, 1, {0.5f, 0.0f, 1.0f, 2.0f, -1.0f, std::nanf("")});
  gridrt::writeImage(path, film);

  ImageData img = gridrt::readImage(path);
  ASSERT_EQ(img.width, 2);
  ASSERT_EQ(img.height, 1);
  ASSERT_EQ(img.channels, 3);
  const std::vector<float> expected{0.7354f, 0.0f, 1.0f, 1.0f, 0.0f, 0.0f};
  for (size_t i = 0; i < expected.size(); ++i)
    EXPECT_NEAR(img.pixels[i], expected[i], 1.0f / 255.0f) << "value " << i;
}

// Every 8-bit code is the exact sRGB encoding (in double) rounded to the nearest code,
// except where that encoding lies within kCodeBoundaryGuard codes of a rounding boundary:
// float powf's error (a few ulp, ~1e-5 codes) may round such a value either way. A fast
// approximate pow (OpenImageIO's colorconvert) missed by up to 0.0017 codes (297 of the
// default scene's 921,600 values one code off).
constexpr double kCodeBoundaryGuard = 1e-4;

TEST(ImageOutput, PngCodesAreTheExactSrgbEncodingRounded) {
  const std::string path = freshDir("png_exact") + "/ramp.png";
  const int width = 1024, height = 512;
  Film film = rgbFilm(width, height, std::vector<float>(size_t(3) * width * height));
  const size_t n = film.rgb.size();
  for (size_t k = 0; k < n; ++k) {  // every level of [0, 1], the darks densely (a square ramp)
    const double x = double(k) / double(n - 1);
    film.rgb[k] = float(k % 2 ? x : x * x);
  }
  gridrt::writeImage(path, film);
  ImageData img = gridrt::readImage(path);
  ASSERT_EQ(img.pixels.size(), n);
  size_t judged = 0, off = 0;
  for (size_t k = 0; k < n; ++k) {
    const double v = film.rgb[k];
    const double code =
        255.0 * (v <= 0.0031308 ? 12.92 * v : 1.055 * std::pow(v, 1.0 / 2.4) - 0.055);
    if (std::fabs(code - std::floor(code) - 0.5) < kCodeBoundaryGuard) continue;
    ++judged;
    off += std::lround(img.pixels[k] * 255.0f) != std::lround(code);
  }
  EXPECT_GT(judged, n - n / 1000);
  EXPECT_EQ(off, 0u);
}

TEST(ImageOutput, JpegIsSrgbEncodedToo) {
  const std::string path = freshDir("jpg") + "/out.jpg";
  Film film = rgbFilm(8, 8, std::vector<float>(3 * 8 * 8, 0.5f));
  gridrt::writeImage(path, film);

  ImageData img = gridrt::readImage(path);
  ASSERT_EQ(img.pixels.size(), film.rgb.size());
  for (float v : img.pixels) EXPECT_NEAR(v, 0.7354f, 3.0f / 255.0f);  // lossy, uniform block
}

TEST(ImageOutput, ExrKeepsLinearFloatsExactly) {
  const std::string path = freshDir("exr") + "/out.exr";
  Film film = rgbFilm(
      2, 2,
      {0.1f, 0.5f, 1.0f, 2.75f, 1e-4f, 123.456f, -0.5f, 0.0f, 1e6f, 0.333333f, 7.0f, 0.7354f});
  gridrt::writeImage(path, film);

  ImageData img = gridrt::readImage(path);
  EXPECT_EQ(img.width, 2);
  EXPECT_EQ(img.height, 2);
  EXPECT_EQ(img.channels, 3);
  EXPECT_EQ(img.pixels, film.rgb);  // row 0 stays on top, values bit-exact
}

TEST(ImageOutput, SingleChannelAovRoundTripIsExact) {
  const std::string path = freshDir("aov1") + "/primid.exr";
  // Primitive ids with -1 for misses, and the largest exactly representable integer 2^24.
  const std::vector<float> data{-1.0f, 0.0f, 948.0f, 16777216.0f, 0.25f, 3.5e10f};
  gridrt::writeAov(path, 3, 2, 1, data);

  ImageData img = gridrt::readImage(path);
  EXPECT_EQ(img.width, 3);
  EXPECT_EQ(img.height, 2);
  EXPECT_EQ(img.channels, 1);
  EXPECT_EQ(img.pixels, data);
}

TEST(ImageOutput, ThreeChannelAovRoundTripIsExact) {
  const std::string path = freshDir("aov3") + "/normal.exr";
  const std::vector<float> data{0.0f, 0.0f, 1.0f, -0.577350f, 0.577350f, -0.577350f};
  gridrt::writeAov(path, 2, 1, 3, data);

  ImageData img = gridrt::readImage(path);
  EXPECT_EQ(img.channels, 3);
  EXPECT_EQ(img.pixels, data);
}

TEST(ImageOutput, UnsupportedExtensionIsRejectedNamingTheFile) {
  const std::string dir = freshDir("ext");
  const std::string path = dir + "/out.xyz";
  Film film = rgbFilm(1, 1, {0.5f, 0.5f, 0.5f});

  std::string message = renderErrorOf([&] { gridrt::writeImage(path, film); });
  EXPECT_NE(message.find("'" + path + "'"), std::string::npos) << message;
  EXPECT_NE(message.find("unsupported output format '.xyz' (use .png, .jpg or .exr)"),
            std::string::npos)
      << message;
  EXPECT_THROW(gridrt::validateOutputPath(path), RenderError);
  EXPECT_THROW(gridrt::validateOutputPath(dir + "/no_extension"), RenderError);
  // AOVs must keep floats exactly: 8-bit formats are refused.
  EXPECT_THROW(gridrt::writeAov(dir + "/depth.png", 1, 1, 1, {1.0f}), RenderError);
  EXPECT_TRUE(listDir(dir).empty());
}

TEST(ImageOutput, ValidateOutputPathAcceptsSupportedFormats) {
  const std::string dir = freshDir("valid");
  for (const char* name : {"a.png", "a.PNG", "a.jpg", "a.jpeg", "a.exr", "a.hdr", "a.tif"})
    EXPECT_NO_THROW(gridrt::validateOutputPath(dir + "/" + name)) << name;
  EXPECT_NO_THROW(gridrt::validateOutputPath(dir + "/depth.exr", gridrt::OutputKind::Aov));
  EXPECT_TRUE(listDir(dir).empty());  // validation writes nothing
}

TEST(ImageOutput, MissingDirectoryIsRejectedBeforeWriting) {
  const std::string path = freshDir("missing") + "/no/such/dir/out.png";
  Film film = rgbFilm(1, 1, {0.5f, 0.5f, 0.5f});

  std::string message = renderErrorOf([&] { gridrt::writeImage(path, film); });
  EXPECT_EQ(message.rfind("cannot write '" + path + "': ", 0), 0u) << message;
  EXPECT_NE(message.find("does not exist"), std::string::npos) << message;
  EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  EXPECT_THROW(gridrt::validateOutputPath(path), RenderError);
  EXPECT_THROW(gridrt::writeAov(path + ".exr", 1, 1, 1, {1.0f}), RenderError);
}

TEST(ImageOutput, FailedWriteLeavesPreviousFileUntouched) {
  const std::string dir = freshDir("untouched");
  const std::string path = dir + "/out.png";
  gridrt::writeImage(path, rgbFilm(2, 2, std::vector<float>(12, 0.25f)));
  const std::string before = fileBytes(path);
  ASSERT_FALSE(before.empty());

  Film inconsistent = rgbFilm(2, 2, std::vector<float>(11, 1.0f));  // one value short
  std::string message = renderErrorOf([&] { gridrt::writeImage(path, inconsistent); });
  EXPECT_NE(message.find("'" + path + "'"), std::string::npos) << message;
  EXPECT_THROW(gridrt::writeImage(path, rgbFilm(0, 2, {})), RenderError);
  EXPECT_THROW(gridrt::writeAov(path + ".exr", 2, 2, 1, {1.0f}), RenderError);

  EXPECT_EQ(fileBytes(path), before);
  EXPECT_EQ(listDir(dir), std::vector<std::string>{"out.png"});
}

TEST(ImageOutput, NoTemporaryFilesLeftAfterSuccessOrFailure) {
  const std::string dir = freshDir("temps");
  Film film = rgbFilm(4, 3, std::vector<float>(36, 0.5f));
  gridrt::writeImage(dir + "/a.png", film);
  gridrt::writeImage(dir + "/a.png", film);  // overwriting an existing file
  gridrt::writeImage(dir + "/b.exr", film);
  gridrt::writeAov(dir + "/c.exr", 4, 3, 1, std::vector<float>(12, 948.0f));
  fs::create_directory(dir + "/d.png");  // a directory where the image should go
  EXPECT_THROW(gridrt::writeImage(dir + "/d.png", film), RenderError);
  EXPECT_THROW(gridrt::writeImage(dir + "/e.xyz", film), RenderError);
  EXPECT_THROW(gridrt::writeImage(dir + "/f.png", rgbFilm(4, 3, {})), RenderError);

  EXPECT_EQ(listDir(dir), (std::vector<std::string>{"a.png", "b.exr", "c.exr", "d.png"}));
}

TEST(ImageOutput, ReadingAMissingFileThrowsNamingIt) {
  const std::string path = freshDir("read") + "/absent.exr";
  std::string message = renderErrorOf([&] { gridrt::readImage(path); });
  EXPECT_EQ(message.rfind("cannot read '" + path + "': ", 0), 0u) << message;
  EXPECT_EQ(message.find('\n'), std::string::npos) << message;
}

// A film with alpha: pixels the background alone (alpha 0), half covered by 0.8 grey, and
// covered.
Film filmWithAlpha() {
  Film film = rgbFilm(3, 1, {0.2f, 0.4f, 0.6f, 0.5f, 0.6f, 0.7f, 0.9f, 0.1f, 0.3f});
  film.alpha = {0.0f, 0.5f, 1.0f};
  film.background = {0.2f, 0.4f, 0.6f};
  return film;
}

TEST(ImageOutput, FloatFilesHoldColourPremultipliedByAlpha) {
  const std::string dir = freshDir("alpha");
  for (const char* name : {"/out.exr", "/out.tif"}) {
    gridrt::writeImage(dir + name, filmWithAlpha());
    const gridrt::LayeredImage image = gridrt::readLayeredImage(dir + name);
    ASSERT_EQ(image.channels.size(), 4u) << name;
    const std::vector<std::string> names{"R", "G", "B", "A"};
    const std::vector<std::vector<float>> want{
        {0.0f, 0.5f - 0.5f * 0.2f, 0.9f},  // the background's share taken out
        {0.0f, 0.6f - 0.5f * 0.4f, 0.1f},
        {0.0f, 0.7f - 0.5f * 0.6f, 0.3f},
        {0.0f, 0.5f, 1.0f}};
    for (size_t c = 0; c < 4; ++c) {
      EXPECT_EQ(image.channels[c].name, names[c]) << name;
      EXPECT_EQ(image.channels[c].floats, want[c]) << name << " " << names[c];
    }
    // OpenEXR keeps the background as an attribute; TIFF has no place for it.
    const std::array<float, 3> background = name == std::string("/out.exr")
                                                ? std::array<float, 3>{0.2f, 0.4f, 0.6f}
                                                : std::array<float, 3>{0.0f, 0.0f, 0.0f};
    EXPECT_EQ(image.background, background) << name;
  }
}

TEST(ImageOutput, APngHoldsAlphaAndFormatsWithoutItRefuseIt) {
  const std::string dir = freshDir("alpha_formats");
  gridrt::writeImage(dir + "/out.png", filmWithAlpha());
  const ImageData png = gridrt::readImage(dir + "/out.png");
  ASSERT_EQ(png.channels, 4);
  EXPECT_EQ(png.pixels[3], 0.0f);
  EXPECT_NEAR(png.pixels[7], 128.0f / 255.0f, 1e-6f);
  EXPECT_EQ(png.pixels[11], 1.0f);
  for (const char* name : {"/out.jpg", "/out.hdr"}) {
    const std::string message =
        renderErrorOf([&] { gridrt::writeImage(dir + name, filmWithAlpha()); });
    EXPECT_NE(message.find(dir + name), std::string::npos) << message;
    EXPECT_NE(message.find("holds no alpha channel"), std::string::npos) << message;
    EXPECT_FALSE(fs::exists(dir + name));
  }
}

// A multi-layer EXR keeps 32-bit unsigned ids exactly beside float channels: 2^24 + 1 (no
// float holds it) and a miss, -1, as 2^32 - 1.
TEST(ImageOutput, LayeredExrKeepsEvery32BitsOfIds) {
  const std::string path = freshDir("layers") + "/layers.exr";
  gridrt::LayeredImage image;
  image.width = 3;
  image.height = 1;
  image.channels.push_back(gridrt::floatChannel("depth.Z", {1.5f, -1.0f, 2.25f}, 1, 0));
  image.channels.push_back(gridrt::idChannel("primid.id", {16777217, -1, 2147483647}));
  gridrt::writeLayeredImage(path, image, gridrt::OutputKind::Layers);
  const gridrt::LayeredImage back = gridrt::readLayeredImage(path);
  const int id = gridrt::channelIndex(back, "primid.id"),
            depth = gridrt::channelIndex(back, "depth.Z");
  ASSERT_GE(id, 0);
  ASSERT_GE(depth, 0);
  EXPECT_EQ(back.channels[id].type, gridrt::SampleType::UInt);
  EXPECT_EQ(back.channels[id].uints, (std::vector<uint32_t>{16777217u, 0xFFFFFFFFu, 2147483647u}));
  EXPECT_EQ(back.channels[depth].type, gridrt::SampleType::Float);
  EXPECT_EQ(back.channels[depth].floats, (std::vector<float>{1.5f, -1.0f, 2.25f}));
  const std::string message = renderErrorOf([&] {
    gridrt::writeLayeredImage(freshDir("layers_tif") + "/layers.tif", image,
                              gridrt::OutputKind::Layers);
  });
  EXPECT_NE(message.find("unsupported multi-layer format"), std::string::npos) << message;
}
