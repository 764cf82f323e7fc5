// tools/mesh_to_gltf.py: PLY (ASCII, binary little-endian) and OBJ meshes become .glb files
// that gridrt's loader reads back with the same triangles (fan-triangulated polygons,
// negative OBJ indices). Skipped when python3 is not installed.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

#include "errors.h"
#include "gltf_loader.h"
#include "run_command.h"
#include "test_support.h"

namespace {

using gridrt::test::runCommand;
using gridrt::test::sourcePath;
using gridrt::test::tempPath;

void writeBytes(const std::string& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary);
  out.write(bytes.data(), std::streamsize(bytes.size()));
}

// Runs the converter on `mesh` (written to a temp file named `name`) and loads the result.
gridrt::Scene convertAndLoad(const std::string& name, const std::string& mesh) {
  const std::string in = tempPath(name), out = tempPath(name + ".glb");
  writeBytes(in, mesh);
  auto r = runCommand({"python3", sourcePath("tools/mesh_to_gltf.py"), in, out});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  return gridrt::loadGltfFile(out);
}

bool havePython() { return std::system("command -v python3 >/dev/null 2>&1") == 0; }

// The unit square z = 0 as a quad: fan-triangulated into (0,1,2) and (0,2,3).
const float kSquare[4][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
const int kFan[6] = {0, 1, 2, 0, 2, 3};

void expectSquare(const gridrt::Scene& scene) {
  ASSERT_EQ(scene.triangleCount(), 2u);
  for (int k = 0; k < 6; ++k)
    for (int a = 0; a < 3; ++a)
      EXPECT_EQ(scene.positions[k][a], kSquare[kFan[k]][a]) << "corner " << k << " axis " << a;
}

TEST(MeshToGltf, AsciiPlyQuadBecomesTwoTriangles) {
  if (!havePython()) GTEST_SKIP() << "python3 is not installed";
  expectSquare(convertAndLoad("square.ply",
                              "ply\nformat ascii 1.0\ncomment a unit square\n"
                              "element vertex 4\nproperty float x\nproperty float y\n"
                              "property float z\nproperty uchar red\n"
                              "element face 1\nproperty list uchar int vertex_indices\n"
                              "end_header\n0 0 0 9\n1 0 0 9\n1 1 0 9\n0 1 0 9\n4 0 1 2 3\n"));
}

TEST(MeshToGltf, BinaryLittleEndianPlyIsRead) {
  if (!havePython()) GTEST_SKIP() << "python3 is not installed";
  std::string ply =
      "ply\nformat binary_little_endian 1.0\nelement vertex 4\nproperty float x\n"
      "property float y\nproperty float z\nelement face 1\n"
      "property list uchar uint vertex_indices\nend_header\n";
  ply.append(reinterpret_cast<const char*>(kSquare), sizeof kSquare);  // little-endian host
  ply.push_back(char(4));
  const uint32_t quad[4] = {0, 1, 2, 3};
  ply.append(reinterpret_cast<const char*>(quad), sizeof quad);
  expectSquare(convertAndLoad("square_binary.ply", ply));
}

TEST(MeshToGltf, ObjWithNegativeIndicesAndSlashesIsRead) {
  if (!havePython()) GTEST_SKIP() << "python3 is not installed";
  expectSquare(convertAndLoad("square.obj",
                              "# unit square\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvn 0 0 1\n"
                              "vt 0 0\nf -4/1/1 -3//1 3/1 4\n"));
}

TEST(MeshToGltf, OutOfRangeIndexIsAnErrorAndWritesNothing) {
  if (!havePython()) GTEST_SKIP() << "python3 is not installed";
  const std::string in = tempPath("bad.obj"), out = tempPath("bad.glb");
  writeBytes(in, "v 0 0 0\nv 1 0 0\nf 1 2 3\n");
  auto r = runCommand({"python3", sourcePath("tools/mesh_to_gltf.py"), in, out});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("out of range"), std::string::npos) << r.err;
  EXPECT_FALSE(gridrt::test::fileExists(out));
}

}  // namespace

namespace {

// A .gltf target gets glTF JSON (its buffer a data URI), not GLB bytes under a JSON name.
TEST(MeshToGltf, GltfTargetIsJsonWithTheSameTriangles) {
  if (!havePython()) GTEST_SKIP() << "python3 is not installed";
  const std::string in = tempPath("square_json.obj"), out = tempPath("square_json.gltf");
  writeBytes(in, "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n");
  auto r = runCommand({"python3", sourcePath("tools/mesh_to_gltf.py"), in, out});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string text = gridrt::test::readWholeFile(out);
  ASSERT_FALSE(text.empty());
  EXPECT_EQ(text.front(), '{');
  EXPECT_NE(text.find("\"uri\":\"data:application/octet-stream;base64,"), std::string::npos);
  expectSquare(gridrt::loadGltfFile(out));
}

TEST(MeshToGltf, OtherTargetsAreRefused) {
  if (!havePython()) GTEST_SKIP() << "python3 is not installed";
  const std::string in = tempPath("square_txt.obj");
  writeBytes(in, "v 0 0 0\nv 1 0 0\nv 1 1 0\nf 1 2 3\n");
  auto r = runCommand({"python3", sourcePath("tools/mesh_to_gltf.py"), in, tempPath("x.txt")});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("must be .glb"), std::string::npos) << r.err;
}

// Asking a tool for help is not a mistake: exit 0, the usage on standard output.
TEST(Tools, HelpExitsZero) {
  if (!havePython()) GTEST_SKIP() << "python3 is not installed";
  for (const std::vector<std::string>& argv :
       {std::vector<std::string>{"python3", sourcePath("tools/mesh_to_gltf.py"), "--help"},
        std::vector<std::string>{GRIDRT_MERGE_TILES, "--help"}}) {
    auto r = runCommand(argv);
    EXPECT_EQ(r.exit_code, 0) << argv[1] << ": " << r.err;
    EXPECT_NE(r.out.find("usage: "), std::string::npos) << r.out;
  }
}

// A tool that needs numpy and OpenImageIO (.venv) run by a Python without them says so in
// one line (exit 1) instead of a traceback. The missing package is simulated by a module
// that fails to import, first on the path.
TEST(Tools, AMissingPythonPackageIsOneLine) {
  if (!havePython()) GTEST_SKIP() << "python3 is not installed";
  const std::string shadow = gridrt::test::freshDir("missing_numpy");
  std::ofstream(shadow + "/numpy.py")
      << "raise ModuleNotFoundError(\"No module named 'numpy'\", name='numpy')\n";
  setenv("PYTHONPATH", shadow.c_str(), 1);
  for (const char* tool :
       {"tools/heatmap.py", "tools/compare_renders.py", "tools/accuracy_sweep.py"}) {
    auto r = runCommand({"python3", sourcePath(tool), "--help"});
    EXPECT_EQ(r.exit_code, 1) << tool << ": " << r.err;
    EXPECT_NE(r.err.find("the Python package 'numpy' is missing"), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find("Traceback"), std::string::npos) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  }
  unsetenv("PYTHONPATH");
}

}  // namespace
