// glTF alphaMode rendered by gridrt from the command line, against what the geometry says
// each pixel must show, worked out here independently of the renderer.
//
// MASK: a 4 x 4 unit quad at z = 1 whose 4 x 4 texture cuts holes (texel alpha below
// alphaCutoff) above a white floor at z = 0, seen straight down by an orthographic camera,
// 16 x 16 pixels a texel; a directional light 45 degrees off the vertical, so that a floor
// point's shadow ray crosses the quad one texel further along x. Camera rays must see the
// floor exactly through the holes, shadow rays reach the light exactly through the holes,
// on every intersector (the closest hit past a hole decided by each).
//
// BLEND: the same quad of alpha 0.25 with the light straight above: a pixel is a quarter
// the quad's light and three quarters the floor's, which itself gets three quarters of
// the light.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <string>
#include <vector>

#include "gltf_document_builder.h"
#include "image_output.h"
#include "png_encoding.h"
#include "run_command.h"
#include "test_support.h"

namespace gridrt {
namespace {

constexpr int kPixels = 64;              // the image, kPixels x kPixels
constexpr double kPixelsPerUnit = 16.0;  // the camera sees [0, 4] x [0, 4]
constexpr double kPi = 3.14159265358979;
// Lit and shadowed floor pixels differ by 2/pi x cos 45 = 0.45; half of it tells them apart.
constexpr double kLitThreshold = 0.05 + 0.225;
// A few float roundings of values near 1 along the shading of two surfaces.
constexpr double kShadingTolerance = 1e-5;

// Texel (c, r) of the mask, r = 0 the top row (glTF's v = 0), is solid or a hole: pairs of
// columns, alternating by row, so that a floor point seen through a hole has its shadow
// ray cross a hole (lit), a solid texel (shadowed) or nothing (lit).
bool solidTexel(int c, int r) { return (c / 2 + r) % 2 == 0; }
constexpr uint8_t kSolidAlpha = 160, kHoleAlpha = 100;  // 0.63 and 0.39 about the 0.5 cutoff

// Whether the quad is solid above the floor point (x, y): texel column floor(x), row
// 3 - floor(y) (v = 1 - y / 4); outside the quad nothing is there.
bool solidAt(double x, double y) {
  if (x < 0 || x >= 4 || y < 0 || y >= 4) return false;
  return solidTexel(int(std::floor(x)), 3 - int(std::floor(y)));
}

// The scene: quad (triangles 0, 1, material 0) over the floor (triangles 2, 3, material 1).
// `quad_material`: the quad's material JSON; `light_rotation`: more members of the light's
// node ("" points it straight down); `png`: the quad's texture (none when empty).
std::string sceneDocument(const std::string& quad_material, const std::string& light_rotation,
                          const std::vector<unsigned char>& png) {
  test::GltfDocumentBuilder doc;
  const int quad = doc.floats({0, 0, 1, 4, 0, 1, 4, 4, 1, 0, 4, 1}, "VEC3");
  const int uv = doc.floats({0, 1, 1, 1, 1, 0, 0, 0}, "VEC2");
  const int floor = doc.floats({-10, -10, 0, 14, -10, 0, 14, 14, 0, -10, 14, 0}, "VEC3");
  const std::vector<uint16_t> indices = {0, 1, 2, 0, 2, 3};
  const int index = doc.addAccessor(test::bytesOf(indices), test::kGltfUnsignedShort, 6, "SCALAR");
  std::string images;
  if (!png.empty())
    images =
        ",\"textures\":[{\"source\":0,\"sampler\":0}],"
        "\"samplers\":[{\"magFilter\":9728,\"minFilter\":9728}],"
        "\"images\":[{\"bufferView\":" +
        std::to_string(doc.addView(std::string(png.begin(), png.end()))) +
        ",\"mimeType\":\"image/png\"}]";
  auto primitive = [&](int positions, int material) {
    return "{\"primitives\":[{\"attributes\":{\"POSITION\":" + std::to_string(positions) +
           ",\"TEXCOORD_0\":" + std::to_string(uv) + "},\"indices\":" + std::to_string(index) +
           ",\"material\":" + std::to_string(material) + "}]}";
  };
  return doc.json(
      "\"scene\":0,\"scenes\":[{\"nodes\":[0,1,2,3]}],"
      "\"nodes\":[{\"mesh\":0},{\"mesh\":1},{\"camera\":0,\"translation\":[2,2,5]},"
      "{\"extensions\":{\"KHR_lights_punctual\":{\"light\":0}}" +
      light_rotation +
      "}],"
      "\"cameras\":[{\"type\":\"orthographic\",\"orthographic\":{\"xmag\":2,\"ymag\":2,"
      "\"znear\":0.1,\"zfar\":10}}],"
      "\"extensionsUsed\":[\"KHR_lights_punctual\"],"
      "\"extensions\":{\"KHR_lights_punctual\":{\"lights\":[{\"type\":\"directional\","
      "\"intensity\":2}]}},"
      "\"meshes\":[" +
      primitive(quad, 0) + "," + primitive(floor, 1) +
      "],"
      "\"materials\":[" +
      quad_material + ",{\"pbrMetallicRoughness\":{\"metallicFactor\":0,\"roughnessFactor\":1}}]" +
      images);
}

// The mask's RGBA texels: white, alpha solid or hole.
std::vector<unsigned char> maskPng() {
  std::vector<uint8_t> texels;
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c)
      texels.insert(texels.end(), {255, 255, 255, solidTexel(c, r) ? kSolidAlpha : kHoleAlpha});
  return test::encodePng(4, 4, 4, texels);
}

const char* kMaskMaterial =
    "{\"alphaMode\":\"MASK\",\"pbrMetallicRoughness\":{\"baseColorTexture\":{\"index\":0},"
    "\"metallicFactor\":0,\"roughnessFactor\":1}}";
// The light points along (-1, 0, -1) / sqrt 2: -Z turned 45 degrees about +Y.
const char* kTiltedLight = ",\"rotation\":[0,0.38268343236508978,0,0.92387953251128674]";

struct Render {
  test::CommandResult result;
  ImageData beauty, primid;
};

Render render(const std::string& name, const std::string& document,
              const std::vector<std::string>& accel) {
  const std::string dir = test::freshDir(name);
  const std::string scene = dir + "/scene.gltf";
  std::ofstream(scene, std::ios::binary) << document;
  std::vector<std::string> argv = {test::gridrtBinary(),
                                   scene,
                                   "--width",
                                   std::to_string(kPixels),
                                   "--height",
                                   std::to_string(kPixels),
                                   "-o",
                                   dir + "/beauty.exr",
                                   "--aov",
                                   "primid=" + dir + "/primid.exr"};
  argv.insert(argv.end(), accel.begin(), accel.end());
  Render r;
  r.result = test::runCommand(argv);
  if (r.result.exit_code == 0) {
    r.beauty = readImage(dir + "/beauty.exr");
    r.primid = readImage(dir + "/primid.exr");
  }
  return r;
}

class AlphaMask : public ::testing::TestWithParam<std::vector<std::string>> {};

TEST_P(AlphaMask, CameraAndShadowRaysPassExactlyTheHoles) {
  const Render r =
      render("mask", sceneDocument(kMaskMaterial, kTiltedLight, maskPng()), GetParam());
  ASSERT_EQ(r.result.exit_code, 0) << r.result.err;
  EXPECT_EQ(r.result.err.find("alphaMode"), std::string::npos) << r.result.err;
  ASSERT_EQ(r.primid.width, kPixels);
  ASSERT_EQ(r.beauty.channels, 3);
  size_t wrong_surface = 0, wrong_light = 0, floor_pixels = 0, shadowed = 0, lit_through = 0;
  for (int j = 0; j < kPixels; ++j)
    for (int i = 0; i < kPixels; ++i) {
      const double x = (i + 0.5) / kPixelsPerUnit, y = 4.0 - (j + 0.5) / kPixelsPerUnit;
      const size_t p = size_t(j) * kPixels + i;
      const bool on_quad = solidAt(x, y);
      const float id = r.primid.pixels[p];
      wrong_surface += on_quad ? !(id == 0 || id == 1) : !(id == 2 || id == 3);
      // The floor's shadow ray crosses z = 1 one unit further along x; the quad is lit.
      const bool lit = on_quad || !solidAt(x + 1.0, y);
      floor_pixels += !on_quad;
      shadowed += !lit;
      lit_through += !on_quad && lit && x + 1.0 < 4.0;  // its shadow ray passes a hole
      wrong_light += (r.beauty.pixels[3 * p] > kLitThreshold) != lit;
    }
  EXPECT_EQ(wrong_surface, 0u);
  EXPECT_EQ(wrong_light, 0u);
  // The pattern has holes with the floor behind them shadowed, and lit through a hole.
  EXPECT_GT(shadowed, 0u);
  EXPECT_GT(lit_through, 0u);
  EXPECT_GT(floor_pixels, shadowed + lit_through);
}

INSTANTIATE_TEST_SUITE_P(
    EveryIntersector, AlphaMask,
    ::testing::Values(std::vector<std::string>{"--accel", "gridrt"},
                      std::vector<std::string>{"--accel", "gridrt", "--grid", "4,4,2"},
                      std::vector<std::string>{"--accel", "dda", "--grid", "4,4,2"},
                      std::vector<std::string>{"--accel", "brute"},
                      std::vector<std::string>{"--accel", "reference"}));

TEST(AlphaMaskCutoff, ACutoffBelowEveryTexelMakesTheQuadSolid) {
  const std::string material =
      "{\"alphaMode\":\"MASK\",\"alphaCutoff\":0.3,\"pbrMetallicRoughness\":{\"baseColorTexture\":"
      "{\"index\":0},\"metallicFactor\":0,\"roughnessFactor\":1}}";
  const Render r = render("cutoff", sceneDocument(material, kTiltedLight, maskPng()), {});
  ASSERT_EQ(r.result.exit_code, 0) << r.result.err;
  size_t floor_seen = 0;
  for (float id : r.primid.pixels) floor_seen += id >= 2;
  EXPECT_EQ(floor_seen, 0u);
}

// The quad's alpha a = 0.25 with the light straight down (cos 1): the quad alone gives
// ambient + 2/pi; the floor behind it ambient + (1 - a) 2/pi.
TEST(AlphaBlend, APixelIsTheAlphaShareOfTheSurfaceAndTheRestOfWhatLiesBehind) {
  const std::string material =
      "{\"alphaMode\":\"BLEND\",\"pbrMetallicRoughness\":{\"baseColorFactor\":[1,1,1,0.25],"
      "\"metallicFactor\":0,\"roughnessFactor\":1}}";
  const double a = 0.25, ambient = 0.05, direct = 2.0 / kPi;
  const double want = a * (ambient + direct) + (1 - a) * (ambient + (1 - a) * direct);
  for (const auto& accel : {std::vector<std::string>{"--accel", "gridrt"},
                            std::vector<std::string>{"--accel", "brute"}}) {
    const Render r = render("blend", sceneDocument(material, "", {}), accel);
    ASSERT_EQ(r.result.exit_code, 0) << r.result.err;
    size_t off = 0;
    for (size_t p = 0; p < r.primid.pixels.size(); ++p) {
      EXPECT_TRUE(r.primid.pixels[p] == 0 || r.primid.pixels[p] == 1);  // the quad is hit first
      for (int c = 0; c < 3; ++c)
        off += std::fabs(r.beauty.pixels[3 * p + c] - want) > kShadingTolerance;
    }
    EXPECT_EQ(off, 0u) << accel[1] << ": pixel 0 is " << r.beauty.pixels[0] << ", want " << want;
  }
}

}  // namespace
}  // namespace gridrt
