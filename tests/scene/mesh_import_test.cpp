// Mesh files read through assimp (mesh_import.h): small OBJ (with its MTL), PLY and STL
// files written here, loaded, their triangles, normals and colours checked against values
// worked out by hand.
#include "mesh_import.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <string>
#include <vector>

#include "errors.h"
#include "test_support.h"

namespace gridrt {
namespace {

std::string writeFile(const std::string& dir, const std::string& name, const std::string& text) {
  const std::string path = dir + "/" + name;
  std::ofstream(path, std::ios::binary) << text;
  return path;
}

using Triangle = std::array<glm::vec3, 3>;

// The scene's triangles, each turned (its winding kept) to start at its smallest vertex.
std::vector<Triangle> trianglesOf(const Scene& s) {
  std::vector<Triangle> out;
  auto less = [](const glm::vec3& a, const glm::vec3& b) {
    return std::lexicographical_compare(&a.x, &a.x + 3, &b.x, &b.x + 3);
  };
  for (size_t t = 0; t < s.triangleCount(); ++t) {
    Triangle tri = {s.positions[3 * t], s.positions[3 * t + 1], s.positions[3 * t + 2]};
    std::rotate(tri.begin(), std::min_element(tri.begin(), tri.end(), less), tri.end());
    out.push_back(tri);
  }
  return out;
}

std::string errorOf(const std::string& path) {
  return test::errorOf<SceneError>([&] { importMeshFile(path); });
}

const std::string kObj =
    "mtllib colours.mtl\n"
    "v 0 0 0\nv 2 0 0\nv 2 1 0\nv 0 1 0\nv 0 0 3\n"
    "vn 0 0 1\nvn 0 -1 0\n"
    "usemtl red\n"
    "f 1//1 2//1 3//1 4//1\n"  // a quad: two triangles
    "usemtl blue\n"
    "f 1//2 5//2 2//2\n";
const std::string kMtl =
    "newmtl red\nKd 0.8 0.1 0.05\nKs 0.5 0.5 0.5\nNs 98\n"
    "newmtl blue\nKd 0.1 0.2 0.9\n";

TEST(MeshImport, ObjWithMtlGivesItsTrianglesNormalsAndColours) {
  const std::string dir = test::freshDir("obj");
  writeFile(dir, "colours.mtl", kMtl);
  const Scene s = importMeshFile(writeFile(dir, "shape.obj", kObj));
  ASSERT_EQ(s.triangleCount(), 3u);
  // The quad split along its diagonal from the first corner, counter-clockwise as written.
  const std::vector<Triangle> want = {{glm::vec3(0, 0, 0), glm::vec3(2, 0, 0), glm::vec3(2, 1, 0)},
                                      {glm::vec3(0, 0, 0), glm::vec3(2, 1, 0), glm::vec3(0, 1, 0)},
                                      {glm::vec3(0, 0, 0), glm::vec3(0, 0, 3), glm::vec3(2, 0, 0)}};
  EXPECT_EQ(trianglesOf(s), want);
  ASSERT_EQ(s.normals.size(), 9u);
  for (size_t v = 0; v < 6; ++v) EXPECT_EQ(s.normals[v], glm::vec3(0, 0, 1)) << v;
  for (size_t v = 6; v < 9; ++v) EXPECT_EQ(s.normals[v], glm::vec3(0, -1, 0)) << v;

  const Material& red = s.materials[size_t(s.material_of[0])];
  EXPECT_EQ(s.material_of[1], s.material_of[0]);
  EXPECT_EQ(red.name, "red");
  EXPECT_EQ(red.base_color, glm::vec3(0.8f, 0.1f, 0.05f));
  EXPECT_EQ(red.metallic, 0.0f);
  // Ns 98 is the Phong exponent 2/α² − 2 of α = √(2/100): roughness √α = 0.02^(1/4).
  EXPECT_FLOAT_EQ(red.roughness, 0.376060309f);
  const Material& blue = s.materials[size_t(s.material_of[2])];
  EXPECT_EQ(blue.name, "blue");
  EXPECT_EQ(blue.base_color, glm::vec3(0.1f, 0.2f, 0.9f));
  EXPECT_EQ(blue.roughness, 1.0f);  // no Ks: no highlight
  EXPECT_FALSE(s.has_camera);
  EXPECT_FALSE(s.has_lights);
}

TEST(MeshImport, ObjWithoutMaterialsTakesTheDefaultMaterial) {
  const std::string dir = test::freshDir("bare_obj");
  const Scene s =
      importMeshFile(writeFile(dir, "bare.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nl 1 2\n"));
  ASSERT_EQ(s.triangleCount(), 1u);
  EXPECT_EQ(s.skipped_primitives, 1u);  // the line
  const Material& m = s.materials[size_t(s.material_of[0])];
  EXPECT_EQ(m.base_color, Material{}.base_color);
  EXPECT_EQ(m.roughness, Material{}.roughness);
  EXPECT_TRUE(s.normals.empty());  // the file has none
}

const std::string kPlyHeader =
    "ply\nformat ascii 1.0\nelement vertex 5\nproperty float x\nproperty float y\n"
    "property float z\nproperty uchar red\nproperty uchar green\nproperty uchar blue\n";

TEST(MeshImport, PlyGivesItsTrianglesAndVertexColours) {
  const std::string dir = test::freshDir("ply");
  const std::string path =
      writeFile(dir, "square.ply",
                kPlyHeader +
                    "element face 2\nproperty list uchar int vertex_indices\nend_header\n"
                    "0 0 0 255 0 0\n1 0 0 0 255 0\n1 1 0 0 0 255\n0 1 0 51 102 153\n5 5 5 0 0 0\n"
                    "3 0 1 2\n3 0 2 3\n");
  const Scene s = importMeshFile(path);
  ASSERT_EQ(s.triangleCount(), 2u);
  EXPECT_EQ(s.positions, (std::vector<glm::vec3>{
                             {0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 0, 0}, {1, 1, 0}, {0, 1, 0}}));
  ASSERT_EQ(s.colors.size(), 6u);
  const glm::vec4 red(1, 0, 0, 1), green(0, 1, 0, 1), blue(0, 0, 1, 1);
  const glm::vec4 slate(51 / 255.0f, 102 / 255.0f, 153 / 255.0f, 1);
  const std::vector<glm::vec4> want = {red, green, blue, red, blue, slate};
  for (size_t v = 0; v < 6; ++v)
    for (int c = 0; c < 4; ++c) EXPECT_FLOAT_EQ(s.colors[v][c], want[v][c]) << v << " " << c;
}

TEST(MeshImport, StlGivesItsFacetsWithTheirNormals) {
  const std::string dir = test::freshDir("stl");
  const std::string path = writeFile(dir, "two.stl",
                                     "solid two\n"
                                     "facet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n"
                                     "vertex 0 1 0\nendloop\nendfacet\n"
                                     "facet normal 0 0 0\nouter loop\nvertex 0 0 0\nvertex 0 2 0\n"
                                     "vertex 0 0 2\nendloop\nendfacet\n"
                                     "endsolid two\n");
  const Scene s = importMeshFile(path);
  ASSERT_EQ(s.triangleCount(), 2u);
  EXPECT_EQ(s.positions, (std::vector<glm::vec3>{
                             {0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 0}, {0, 2, 0}, {0, 0, 2}}));
  ASSERT_EQ(s.normals.size(), 6u);
  for (size_t v = 0; v < 3; ++v) EXPECT_EQ(s.normals[v], glm::vec3(0, 0, 1));
  // A zero facet normal is no normal: the face's, cross((0,2,0), (0,0,2)) = +x.
  for (size_t v = 3; v < 6; ++v) EXPECT_EQ(s.normals[v], glm::vec3(1, 0, 0));
}

TEST(MeshImport, TrianglesNoRayCanHitAreDroppedAndCounted) {
  const std::string dir = test::freshDir("degenerate");
  const std::string path =
      writeFile(dir, "degenerate.ply",
                kPlyHeader +
                    "element face 3\nproperty list uchar int vertex_indices\nend_header\n"
                    "0 0 0 0 0 0\n1 0 0 0 0 0\n0 1 0 0 0 0\n2 0 0 0 0 0\nnan 0 0 0 0 0\n"
                    "3 0 1 2\n3 0 1 3\n3 0 1 4\n");  // fine; collinear; a NaN vertex
  const Scene s = importMeshFile(path);
  EXPECT_EQ(s.triangleCount(), 1u);
  EXPECT_EQ(s.dropped_zero_area, 1u);
  EXPECT_EQ(s.dropped_degenerate, 1u);
}

// A file with node transforms (Collada): a triangle scaled by (-2, 1, 1) in a child of a
// node moved by (10, 0, 0). The mirror turns the winding clockwise; vertices 1 and 2 are
// swapped back, so the face still points along +z, as the glTF loader does.
TEST(MeshImport, NodeTransformsMoveTheTrianglesAndMirrorsKeepTheWinding) {
  const std::string dir = test::freshDir("dae");
  const std::string path = writeFile(
      dir, "nodes.dae",
      "<?xml version=\"1.0\" encoding=\"utf-8\"?>\n"
      "<COLLADA xmlns=\"http://www.collada.org/2005/11/COLLADASchema\" version=\"1.4.1\">"
      "<asset><up_axis>Y_UP</up_axis></asset><library_geometries><geometry id=\"tri\"><mesh>"
      "<source id=\"p\"><float_array id=\"pa\" count=\"9\">0 0 0 1 0 0 0 1 0</float_array>"
      "<technique_common><accessor source=\"#pa\" count=\"3\" stride=\"3\">"
      "<param name=\"X\" type=\"float\"/><param name=\"Y\" type=\"float\"/>"
      "<param name=\"Z\" type=\"float\"/></accessor></technique_common></source>"
      "<vertices id=\"v\"><input semantic=\"POSITION\" source=\"#p\"/></vertices>"
      "<triangles count=\"1\"><input semantic=\"VERTEX\" source=\"#v\" offset=\"0\"/>"
      "<p>0 1 2</p></triangles></mesh></geometry></library_geometries>"
      "<library_visual_scenes><visual_scene id=\"s\"><node id=\"parent\">"
      "<translate>10 0 0</translate><node id=\"child\"><scale>-2 1 1</scale>"
      "<instance_geometry url=\"#tri\"/></node></node></visual_scene></library_visual_scenes>"
      "<scene><instance_visual_scene url=\"#s\"/></scene></COLLADA>\n");
  const Scene s = importMeshFile(path);
  EXPECT_EQ(s.positions, (std::vector<glm::vec3>{{10, 0, 0}, {10, 1, 0}, {8, 0, 0}}));
}

TEST(MeshImport, UnreadableFilesAreOneLineErrorsNamingThem) {
  const std::string dir = test::freshDir("unreadable");
  const std::vector<std::pair<std::string, std::string>> cases = {
      {writeFile(dir, "broken.ply", "ply\nformat nonsense 9.0\nend_header\n"), "cannot import: "},
      {writeFile(dir, "range.ply",
                 kPlyHeader + "element face 1\nproperty list uchar int vertex_indices\n"
                              "end_header\n0 0 0 0 0 0\n1 0 0 0 0 0\n0 1 0 0 0 0\n"
                              "1 1 0 0 0 0\n2 2 0 0 0 0\n3 0 1 9\n"),
       ""},
      {dir + "/missing.stl", "cannot open scene '" + dir + "/missing.stl': No such file"},
      {writeFile(dir, "empty.obj", "# nothing\n"), ""}};
  for (const auto& [path, expected] : cases) {
    const std::string message = errorOf(path);
    EXPECT_NE(message, "<no error>") << path;
    EXPECT_NE(message.find(path), std::string::npos) << message;
    EXPECT_NE(message.find(expected), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
}

TEST(MeshImport, OnlyFormatsAssimpReadsOtherThanGltfAreImported) {
  for (const char* path : {"a.obj", "b.PLY", "c.stl", "d.dae"})
    EXPECT_TRUE(isImportedMeshFile(path)) << path;
  for (const char* path : {"a.gltf", "b.GLB", "c.txt", "noextension"})
    EXPECT_FALSE(isImportedMeshFile(path)) << path;
}

}  // namespace
}  // namespace gridrt
