// A textured glTF file rendered by gridrt from the command line: a unit quad seen face-on
// by the file's orthographic camera, 4 x 4 pixels on a 4 x 4 PNG read with a NEAREST
// sampler, so that the albedo AOV of pixel (i, j) is texel (i, j), sRGB undone. The image
// comes from a buffer view, a data URI or a file beside the scene; one outside the scene's
// folder is refused. A vertex-coloured quad gives its interpolated COLOR_0.
#include <gtest/gtest.h>

#include <cstdint>
#include <fstream>
#include <string>
#include <vector>

#include "image_output.h"
#include "png_encoding.h"
#include "run_command.h"
#include "test_support.h"

namespace gridrt {
namespace {

using test::bytesOf;

// OpenImageIO's float sRGB curve against the double formula: within a few float ulps.
constexpr double kSrgbTolerance = 1e-6;
// COLOR_0 interpolated in float from the hit point: a few ulps of 1.
constexpr double kInterpolationTolerance = 1e-5;

constexpr int kSize = 4;

uint8_t code(int c, int r, int channel) {
  const int values[3] = {c * 80, r * 80, 255 - 16 * (c + 4 * r)};
  return uint8_t(values[channel]);
}

std::vector<uint8_t> texelCodes() {
  std::vector<uint8_t> out;
  for (int r = 0; r < kSize; ++r)
    for (int c = 0; c < kSize; ++c)
      for (int ch = 0; ch < 3; ++ch) out.push_back(code(c, r, ch));
  return out;
}

// The quad's glTF document. `image`: the images entry, which may name buffer view 4 (the
// PNG below the geometry); `colours`: COLOR_0 instead of the texture.
std::string quadDocument(const std::string& image, const std::vector<unsigned char>& png,
                         bool colours = false) {
  const std::vector<float> positions = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
  const std::vector<float> uv = {0, 1, 1, 1, 1, 0, 0, 0};  // (x, 1 - y)
  const std::vector<uint16_t> indices = {0, 1, 2, 0, 2, 3};
  // Linear in the position (x, y, 128/255): interpolation is exact everywhere.
  const std::vector<uint8_t> rgba = {0,   0,   128, 255, 255, 0,   128, 255,
                                     255, 255, 128, 255, 0,   255, 128, 255};
  const std::string parts[] = {bytesOf(positions), bytesOf(uv),
                               bytesOf(indices) + std::string(4, '\0'), bytesOf(rgba),
                               std::string(png.begin(), png.end())};
  std::string bin, views;
  for (const std::string& part : parts) {
    views += std::string(views.empty() ? "" : ",") +
             "{\"buffer\":0,\"byteOffset\":" + std::to_string(bin.size()) +
             ",\"byteLength\":" + std::to_string(part.size()) + "}";
    bin += part;
  }
  const std::string attributes =
      colours ? "\"POSITION\":0,\"COLOR_0\":3" : "\"POSITION\":0,\"TEXCOORD_0\":1";
  return "{\"asset\":{\"version\":\"2.0\"},\"scene\":0,\"scenes\":[{\"nodes\":[0,1]}],"
         "\"nodes\":[{\"mesh\":0},{\"camera\":0,\"translation\":[0.5,0.5,2]}],"
         "\"cameras\":[{\"type\":\"orthographic\",\"orthographic\":{\"xmag\":0.5,\"ymag\":0.5,"
         "\"znear\":0.1,\"zfar\":10}}],"
         "\"meshes\":[{\"primitives\":[{\"attributes\":{" +
         attributes +
         "},\"indices\":2,\"material\":0}]}],"
         "\"materials\":[{\"pbrMetallicRoughness\":{" +
         (colours ? "" : "\"baseColorTexture\":{\"index\":0},") +
         "\"metallicFactor\":0}}],"
         "\"textures\":[{\"source\":0,\"sampler\":0}],"
         "\"samplers\":[{\"magFilter\":9728,\"minFilter\":9728}],"
         "\"images\":[" +
         image +
         "],"
         "\"buffers\":[{\"byteLength\":" +
         std::to_string(bin.size()) + ",\"uri\":\"data:application/octet-stream;base64," +
         test::base64(bin) +
         "\"}],"
         "\"bufferViews\":[" +
         views +
         "],"
         "\"accessors\":["
         "{\"bufferView\":0,\"componentType\":5126,\"count\":4,\"type\":\"VEC3\","
         "\"min\":[0,0,0],\"max\":[1,1,0]},"
         "{\"bufferView\":1,\"componentType\":5126,\"count\":4,\"type\":\"VEC2\"},"
         "{\"bufferView\":2,\"componentType\":5123,\"count\":6,\"type\":\"SCALAR\"},"
         "{\"bufferView\":3,\"componentType\":5121,\"normalized\":true,\"count\":4,"
         "\"type\":\"VEC4\"}]}";
}

struct Render {
  test::CommandResult result;
  ImageData albedo;
};

// gridrt on `document` written as scene.gltf into `dir`, with its albedo AOV (not --quiet:
// the warnings are part of what is checked).
Render render(const std::string& dir, const std::string& document) {
  const std::string scene = dir + "/scene.gltf", albedo = dir + "/albedo.exr";
  std::ofstream(scene, std::ios::binary) << document;
  Render r;
  r.result = test::runCommand({test::gridrtBinary(), scene, "--accel", "reference", "--width",
                               std::to_string(kSize), "--height", std::to_string(kSize), "-o",
                               dir + "/beauty.exr", "--aov", "albedo=" + albedo});
  if (r.result.exit_code == 0) r.albedo = readImage(albedo);
  return r;
}

void expectTexels(const Render& r) {
  ASSERT_EQ(r.result.exit_code, 0) << r.result.err;
  EXPECT_EQ(r.result.err.find("warning"), std::string::npos) << r.result.err;
  ASSERT_EQ(r.albedo.width, kSize);
  ASSERT_EQ(r.albedo.channels, 3);
  for (int j = 0; j < kSize; ++j)
    for (int i = 0; i < kSize; ++i)
      for (int ch = 0; ch < 3; ++ch)
        ASSERT_NEAR(r.albedo.pixels[size_t((j * kSize + i) * 3 + ch)],
                    test::srgbDecoded(code(i, j, ch) / 255.0), kSrgbTolerance)
            << "pixel " << i << "," << j << " channel " << ch;
}

TEST(TexturedGltf, AlbedoAovIsTheTextureFromABufferView) {
  const auto png = test::encodePng(kSize, kSize, 3, texelCodes());
  expectTexels(render(test::freshDir("view"),
                      quadDocument("{\"bufferView\":4,\"mimeType\":\"image/png\"}", png)));
}

TEST(TexturedGltf, AlbedoAovIsTheTextureFromADataUri) {
  const auto png = test::encodePng(kSize, kSize, 3, texelCodes());
  const std::string uri =
      "data:image/png;base64," + test::base64(std::string(png.begin(), png.end()));
  expectTexels(render(test::freshDir("datauri"), quadDocument("{\"uri\":\"" + uri + "\"}", {})));
}

TEST(TexturedGltf, AlbedoAovIsTheTextureFromAFileBesideTheScene) {
  const auto png = test::encodePng(kSize, kSize, 3, texelCodes());
  const std::string dir = test::freshDir("external");
  std::ofstream(dir + "/texture.png", std::ios::binary) << std::string(png.begin(), png.end());
  expectTexels(render(dir, quadDocument("{\"uri\":\"texture.png\"}", {})));
}

TEST(TexturedGltf, AnImageOutsideTheScenesFolderIsRefused) {
  const Render r =
      render(test::freshDir("outside"), quadDocument("{\"uri\":\"../texture.png\"}", {}));
  EXPECT_EQ(r.result.exit_code, 1);
  EXPECT_NE(r.result.err.find("contains '..'"), std::string::npos) << r.result.err;
}

TEST(TexturedGltf, AnUndecodableImageIsAWarningAndTheFactorRemains) {
  const std::vector<unsigned char> junk = {'j', 'u', 'n', 'k'};
  const Render r = render(test::freshDir("junk"),
                          quadDocument("{\"bufferView\":4,\"mimeType\":\"image/png\"}", junk));
  ASSERT_EQ(r.result.exit_code, 0) << r.result.err;
  EXPECT_NE(r.result.err.find("warning: image 0: cannot decode"), std::string::npos)
      << r.result.err;
  for (float v : r.albedo.pixels) EXPECT_EQ(v, 1.0f);  // white: baseColorFactor's default
}

TEST(TexturedGltf, VertexColoursAreInterpolatedIntoTheAlbedo) {
  const Render r = render(test::freshDir("colours"), quadDocument("{\"uri\":\"x.png\"}", {}, true));
  ASSERT_EQ(r.result.exit_code, 0) << r.result.err;
  for (int j = 0; j < kSize; ++j)
    for (int i = 0; i < kSize; ++i) {
      const double want[3] = {(i + 0.5) / kSize, 1.0 - (j + 0.5) / kSize, 128.0 / 255.0};
      for (int ch = 0; ch < 3; ++ch)
        EXPECT_NEAR(r.albedo.pixels[size_t((j * kSize + i) * 3 + ch)], want[ch],
                    kInterpolationTolerance)
            << "pixel " << i << "," << j;
    }
}

}  // namespace
}  // namespace gridrt
