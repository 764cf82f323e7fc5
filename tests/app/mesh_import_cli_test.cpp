// Mesh files on the command line (docs/gltf.md, "Other mesh formats"): `gridrt cube.obj`
// renders the cube as its glTF twin renders, bit for bit, framed and lit by the defaults;
// an unreadable file and options a mesh cannot honour fail with one line.
#include <gtest/gtest.h>

#include <cstring>
#include <fstream>
#include <string>
#include <vector>

#include "gltf_document_builder.h"
#include "image_output.h"
#include "run_command.h"
#include "test_support.h"

namespace gridrt {
namespace {

const std::vector<std::string> kSize = {"--width", "64", "--height", "48", "-q"};

test::CommandResult runGridrt(const std::vector<std::string>& args) {
  std::vector<std::string> argv{test::gridrtBinary()};
  argv.insert(argv.end(), args.begin(), args.end());
  argv.insert(argv.end(), kSize.begin(), kSize.end());
  return test::runCommand(argv);
}

std::string writeFile(const std::string& dir, const std::string& name, const std::string& text) {
  const std::string path = dir + "/" + name;
  std::ofstream(path, std::ios::binary) << text;
  return path;
}

// A unit cube, 12 triangles wound outwards.
const std::vector<float> kCorners = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0,
                                     0, 0, 1, 1, 0, 1, 1, 1, 1, 0, 1, 1};
const std::vector<uint16_t> kFaces = {0, 2, 1, 0, 3, 2, 4, 5, 6, 4, 6, 7, 0, 1, 5, 0, 5, 4,
                                      1, 2, 6, 1, 6, 5, 2, 3, 7, 2, 7, 6, 3, 0, 4, 3, 4, 7};

std::string cubeObj() {
  std::string obj = "mtllib cube.mtl\n";
  for (size_t v = 0; v < 8; ++v)
    obj += "v " + std::to_string(int(kCorners[3 * v])) + " " +
           std::to_string(int(kCorners[3 * v + 1])) + " " +
           std::to_string(int(kCorners[3 * v + 2])) + "\n";
  obj += "usemtl orange\n";
  for (size_t t = 0; t < kFaces.size(); t += 3)
    obj += "f " + std::to_string(kFaces[t] + 1) + " " + std::to_string(kFaces[t + 1] + 1) + " " +
           std::to_string(kFaces[t + 2] + 1) + "\n";
  return obj;
}

// The same cube and colour as glTF: Kd 0.9 0.5 0.1 without Ks is a rough dielectric.
std::string cubeGltf() {
  test::GltfDocumentBuilder b;
  const int pos = b.floats(kCorners, "VEC3");
  const int idx =
      b.addAccessor(test::bytesOf(kFaces), test::kGltfUnsignedShort, kFaces.size(), "SCALAR");
  return b.json(
      "\"scene\":0,\"scenes\":[{\"nodes\":[0]}],\"nodes\":[{\"mesh\":0}],"
      "\"materials\":[{\"pbrMetallicRoughness\":{\"baseColorFactor\":[0.9,0.5,0.1,1],"
      "\"metallicFactor\":0,\"roughnessFactor\":1}}],"
      "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":" +
      std::to_string(pos) + "},\"indices\":" + std::to_string(idx) + ",\"material\":0}]}]");
}

bool samePixels(const std::string& a, const std::string& b) {
  const ImageData x = readImage(a), y = readImage(b);
  return x.width == y.width && x.height == y.height && x.channels == y.channels &&
         x.pixels.size() == y.pixels.size() &&
         std::memcmp(x.pixels.data(), y.pixels.data(), x.pixels.size() * sizeof(float)) == 0;
}

TEST(MeshImportCli, AnObjRendersAsItsGltfTwin) {
  const std::string dir = test::freshDir("obj_cli");
  writeFile(dir, "cube.mtl", "newmtl orange\nKd 0.9 0.5 0.1\n");
  const std::string obj = writeFile(dir, "cube.obj", cubeObj());
  const std::string gltf = writeFile(dir, "twin.gltf", cubeGltf());
  const test::CommandResult a =
      runGridrt({obj, "-o", dir + "/obj.png", "--aov", "primid=" + dir + "/obj_id.exr"});
  ASSERT_EQ(a.exit_code, 0) << a.err;
  const test::CommandResult b =
      runGridrt({gltf, "-o", dir + "/gltf.png", "--aov", "primid=" + dir + "/gltf_id.exr"});
  ASSERT_EQ(b.exit_code, 0) << b.err;
  EXPECT_TRUE(samePixels(dir + "/obj_id.exr", dir + "/gltf_id.exr"));
  EXPECT_TRUE(samePixels(dir + "/obj.png", dir + "/gltf.png"));
  // The default framing shows the cube: some pixels hit it, some miss.
  const ImageData ids = readImage(dir + "/obj_id.exr");
  size_t hits = 0;
  for (float id : ids.pixels) hits += id >= 0.0f;
  EXPECT_GT(hits, 0u);
  EXPECT_LT(hits, ids.pixels.size());
}

TEST(MeshImportCli, AnUnreadableMeshFailsWithOneLine) {
  const std::string dir = test::freshDir("broken_cli");
  const std::string ply = writeFile(dir, "broken.ply", "ply\nformat nonsense 9.0\nend_header\n");
  const test::CommandResult r = runGridrt({ply, "-o", dir + "/out.png"});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(r.err.rfind("gridrt: ", 0), 0u) << r.err;
  EXPECT_NE(r.err.find("broken.ply: cannot import: "), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << r.err;
  EXPECT_FALSE(test::fileExists(dir + "/out.png"));
}

TEST(MeshImportCli, CameraAndAnimationOptionsAreUsageErrorsForAMesh) {
  const std::string dir = test::freshDir("options_cli");
  writeFile(dir, "cube.mtl", "newmtl orange\nKd 0.9 0.5 0.1\n");
  const std::string obj = writeFile(dir, "cube.obj", cubeObj());
  for (const std::vector<std::string>& extra :
       {std::vector<std::string>{"--camera", "0"},
        std::vector<std::string>{"--animation", "0", "--time", "1"}}) {
    std::vector<std::string> args = {obj, "-o", dir + "/out.png"};
    args.insert(args.end(), extra.begin(), extra.end());
    const test::CommandResult r = runGridrt(args);
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_NE(r.err.find(extra[0] + " '0'"), std::string::npos) << r.err;
  }
}

}  // namespace
}  // namespace gridrt
