// Tests of the glTF loader: small documents built here with their buffers embedded as base64
// data URIs, plus the model scenes (see scenes/models/SOURCES.md).
#include "gltf_loader.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <limits>
#include <string>
#include <vector>

#include "errors.h"
#include "gltf_compressed_input.h"
#include "gltf_document_builder.h"
#include "test_support.h"

namespace gridrt {
namespace {

using test::base64;
using test::bytesOf;

constexpr int kUByte = 5121, kUShort = 5123, kUInt = 5125, kFloat = 5126;
constexpr float kTol = 1e-5f;

// Builds a glTF document whose single buffer is embedded as a data URI. Each add* call
// appends a bufferView (4-byte aligned) and an accessor over it and returns the accessor.
class GltfBuilder {
 public:
  // `extra`: further accessor members, e.g. ",\"normalized\":true".
  int addAccessor(const std::string& bytes, int component_type, size_t count,
                  const std::string& type, int stride = 0, size_t offset = 0,
                  const std::string& extra = "") {
    const int view = addView(bytes, stride);
    return addRawAccessor(
        "{\"bufferView\":" + std::to_string(view) + ",\"byteOffset\":" + std::to_string(offset) +
        ",\"componentType\":" + std::to_string(component_type) +
        ",\"count\":" + std::to_string(count) + ",\"type\":\"" + type + "\"" + extra + "}");
  }
  // A bufferView over `bytes` (4-byte aligned in the buffer); returns its index.
  int addView(const std::string& bytes, int stride = 0) {
    const size_t view_offset = bin_.size();
    bin_ += bytes;
    bin_.resize((bin_.size() + 3) / 4 * 4, '\0');
    views_.push_back("{\"buffer\":0,\"byteOffset\":" + std::to_string(view_offset) +
                     ",\"byteLength\":" + std::to_string(bytes.size()) +
                     (stride ? ",\"byteStride\":" + std::to_string(stride) : "") + "}");
    return int(views_.size() - 1);
  }
  // An accessor given as JSON; returns its index.
  int addRawAccessor(const std::string& json) {
    accessors_.push_back(json);
    return int(accessors_.size() - 1);
  }
  int vec3(const std::vector<float>& xyz) {
    return addAccessor(bytesOf(xyz), kFloat, xyz.size() / 3, "VEC3");
  }
  int indicesU8(const std::vector<uint8_t>& i) {
    return addAccessor(bytesOf(i), kUByte, i.size(), "SCALAR");
  }
  int indicesU16(const std::vector<uint16_t>& i) {
    return addAccessor(bytesOf(i), kUShort, i.size(), "SCALAR");
  }
  int indicesU32(const std::vector<uint32_t>& i) {
    return addAccessor(bytesOf(i), kUInt, i.size(), "SCALAR");
  }

  // `rest`: the remaining top-level members ("nodes", "meshes", ...) without braces.
  std::string json(const std::string& rest) const {
    std::string doc = "{\"asset\":{\"version\":\"2.0\"}";
    if (!bin_.empty())
      doc += ",\"buffers\":[{\"byteLength\":" + std::to_string(bin_.size()) +
             ",\"uri\":\"data:application/octet-stream;base64," + base64(bin_) + "\"}]" +
             ",\"bufferViews\":[" + join(views_) + "],\"accessors\":[" + join(accessors_) + "]";
    return doc + (rest.empty() ? "" : "," + rest) + "}";
  }
  // The same document as a .glb, buffer 0 its binary chunk.
  std::string glb(const std::string& rest) const {
    return test::makeGlb("{\"asset\":{\"version\":\"2.0\"},\"buffers\":[{\"byteLength\":" +
                             std::to_string(bin_.size()) + "}]," + viewsAndAccessors() +
                             (rest.empty() ? "" : "," + rest) + "}",
                         bin_);
  }
  const std::string& bin() const { return bin_; }
  std::string viewsAndAccessors() const {
    return "\"bufferViews\":[" + join(views_) + "],\"accessors\":[" + join(accessors_) + "]";
  }

 private:
  static std::string join(const std::vector<std::string>& items) {
    std::string out;
    for (const auto& s : items) out += (out.empty() ? "" : ",") + s;
    return out;
  }
  std::string bin_;
  std::vector<std::string> views_, accessors_;
};

std::string primitive(int position, int indices = -1, int material = -1, int mode = 4,
                      int normal = -1) {
  std::string attributes = "\"POSITION\":" + std::to_string(position);
  if (normal >= 0) attributes += ",\"NORMAL\":" + std::to_string(normal);
  std::string p = "{\"attributes\":{" + attributes + "},\"mode\":" + std::to_string(mode);
  if (indices >= 0) p += ",\"indices\":" + std::to_string(indices);
  if (material >= 0) p += ",\"material\":" + std::to_string(material);
  return p + "}";
}

// One mesh of the given primitives on one root node.
std::string singleMesh(const std::string& primitives, const std::string& extra = "") {
  return "\"scene\":0,\"scenes\":[{\"nodes\":[0]}],\"nodes\":[{\"mesh\":0}],"
         "\"meshes\":[{\"primitives\":[" +
         primitives + "]}]" + (extra.empty() ? "" : "," + extra);
}

Scene loadJson(const std::string& json, const GltfLoadOptions& options = {}) {
  return loadGltfFromMemory(reinterpret_cast<const unsigned char*>(json.data()), json.size(), "",
                            "test.gltf", options);
}

using test::errorOf;

#define EXPECT_ERROR(Error, statement, substring)                                      \
  do {                                                                                 \
    const std::string message_ = errorOf<Error>([&] { statement; });                   \
    EXPECT_NE(message_.find(substring), std::string::npos) << message_;                \
    EXPECT_EQ(message_.find('\n'), std::string::npos) << "not one line: " << message_; \
  } while (0)
#define EXPECT_SCENE_ERROR(statement, substring) EXPECT_ERROR(SceneError, statement, substring)
// A bad --camera is the user's mistake, not the file's: a usage error.
#define EXPECT_USAGE_ERROR(statement, substring) EXPECT_ERROR(UsageError, statement, substring)

void expectNear(const glm::vec3& actual, const glm::vec3& expected, float tol = kTol) {
  EXPECT_NEAR(actual.x, expected.x, tol);
  EXPECT_NEAR(actual.y, expected.y, tol);
  EXPECT_NEAR(actual.z, expected.z, tol);
}

std::string readFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

void writeFile(const std::string& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary) << bytes;
}

using test::makeGlb;

const std::vector<float> kQuad = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
const std::vector<glm::vec3> kQuadTriangles = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0},
                                               {0, 0, 0}, {1, 1, 0}, {0, 1, 0}};

void expectQuad(const Scene& scene) {
  ASSERT_EQ(scene.triangleCount(), 2u);
  for (size_t i = 0; i < 6; ++i) expectNear(scene.positions[i], kQuadTriangles[i]);
  EXPECT_TRUE(scene.normals.empty());
  EXPECT_EQ(scene.material_of, (std::vector<int>{0, 0}));
  ASSERT_EQ(scene.materials.size(), 1u);
  EXPECT_EQ(scene.materials[0].name, "default");
}

// ---------------------------------------------------------------------------------------------
// Geometry

TEST(GltfLoader, ReadsUint8Indices) {
  GltfBuilder b;
  int pos = b.vec3(kQuad);
  int idx = b.indicesU8({0, 1, 2, 0, 2, 3});
  expectQuad(loadJson(b.json(singleMesh(primitive(pos, idx)))));
}

TEST(GltfLoader, ReadsUint16Indices) {
  GltfBuilder b;
  int pos = b.vec3(kQuad);
  int idx = b.indicesU16({0, 1, 2, 0, 2, 3});
  expectQuad(loadJson(b.json(singleMesh(primitive(pos, idx)))));
}

TEST(GltfLoader, ReadsUint32Indices) {
  GltfBuilder b;
  int pos = b.vec3(kQuad);
  int idx = b.indicesU32({0, 1, 2, 0, 2, 3});
  expectQuad(loadJson(b.json(singleMesh(primitive(pos, idx)))));
}

TEST(GltfLoader, ReadsNonIndexedTriangles) {
  GltfBuilder b;
  std::vector<float> soup;
  for (const glm::vec3& v : kQuadTriangles) soup.insert(soup.end(), {v.x, v.y, v.z});
  int pos = b.vec3(soup);
  expectQuad(loadJson(b.json(singleMesh(primitive(pos)))));
}

TEST(GltfLoader, ReadsInterleavedPositionsAndNormalsWithStride) {
  GltfBuilder b;
  // Per vertex: position xyz, normal xyz (24-byte stride); normals deliberately not unit.
  std::vector<float> interleaved = {0, 0, 0, 0, 0, 2, 1, 0, 0, 0, 0, 3, 0, 1, 0, 0, 0, 4};
  int pos = b.addAccessor(bytesOf(interleaved), kFloat, 3, "VEC3", 24, 0);
  // The normal accessor shares the bytes through its own view at byteOffset 12.
  int nrm = b.addAccessor(bytesOf(interleaved), kFloat, 3, "VEC3", 24, 12);
  Scene s = loadJson(b.json(singleMesh(primitive(pos, -1, -1, 4, nrm))));
  ASSERT_EQ(s.triangleCount(), 1u);
  expectNear(s.positions[1], {1, 0, 0});
  expectNear(s.positions[2], {0, 1, 0});
  ASSERT_EQ(s.normals.size(), 3u);
  for (const auto& n : s.normals) expectNear(n, {0, 0, 1});
}

TEST(GltfLoader, AppliesTrsParentTimesMatrixChild) {
  GltfBuilder b;
  int pos = b.vec3({0, 0, 0, 1, 0, 0, 0, 1, 0});
  // Parent: T(1,2,3) * R(90 deg about +Y) * S(2); child: matrix translating by (1,0,0).
  const std::string rest =
      "\"scenes\":[{\"nodes\":[0]}],\"nodes\":["
      "{\"translation\":[1,2,3],\"rotation\":[0,0.70710678,0,0.70710678],\"scale\":[2,2,2],"
      "\"children\":[1]},"
      "{\"mesh\":0,\"matrix\":[1,0,0,0, 0,1,0,0, 0,0,1,0, 1,0,0,1]}],"
      "\"meshes\":[{\"primitives\":[" +
      primitive(pos) + "]}]";
  Scene s = loadJson(b.json(rest));
  ASSERT_EQ(s.triangleCount(), 1u);
  // v -> child (+1 x) -> scale 2 -> rotate x->-z, y->y -> translate (1,2,3).
  expectNear(s.positions[0], {1, 2, 1});   // (0,0,0) -> (1,0,0) -> (2,0,0) -> (0,0,-2)
  expectNear(s.positions[1], {1, 2, -1});  // (1,0,0) -> (2,0,0) -> (4,0,0) -> (0,0,-4)
  expectNear(s.positions[2], {1, 4, 1});   // (0,1,0) -> (1,1,0) -> (2,2,0) -> (0,2,-2)
}

TEST(GltfLoader, TransformsNormalsByInverseTranspose) {
  GltfBuilder b;
  int pos = b.vec3({0, 0, 0, 1, 0, 0, 0, 1, 0});
  // A normal at 45 degrees in x/y; a non-uniform scale (4 in x) must tilt it towards y.
  int nrm = b.vec3({1, 1, 0, 1, 1, 0, 1, 1, 0});
  const std::string rest =
      "\"scenes\":[{\"nodes\":[0]}],\"nodes\":[{\"mesh\":0,\"scale\":[4,1,1]}],"
      "\"meshes\":[{\"primitives\":[" +
      primitive(pos, -1, -1, 4, nrm) + "]}]";
  Scene s = loadJson(b.json(rest));
  ASSERT_EQ(s.normals.size(), 3u);
  expectNear(s.normals[0], glm::normalize(glm::vec3(0.25f, 1, 0)));
}

TEST(GltfLoader, KeepsCounterClockwiseWindingUnderMirroringTransform) {
  GltfBuilder b;
  int pos = b.vec3({0, 0, 0, 1, 0, 0, 0, 1, 0});  // counter-clockwise seen from +Z
  const std::string rest =
      "\"scenes\":[{\"nodes\":[0]}],\"nodes\":[{\"mesh\":0,\"scale\":[-1,1,1]}],"
      "\"meshes\":[{\"primitives\":[" +
      primitive(pos) + "]}]";
  Scene s = loadJson(b.json(rest));
  ASSERT_EQ(s.triangleCount(), 1u);
  glm::vec3 n = glm::cross(s.positions[1] - s.positions[0], s.positions[2] - s.positions[0]);
  EXPECT_GT(n.z, 0.0f);
  expectNear(s.positions[0], {0, 0, 0});
}

TEST(GltfLoader, NumbersTrianglesByNodesDepthFirstThenPrimitives) {
  GltfBuilder b;
  int tri = b.vec3({0, 0, 0, 1, 0, 0, 0, 1, 0});
  int tri_y = b.vec3({0, 10, 0, 1, 10, 0, 0, 11, 0});  // second primitive, offset in y
  // File order of nodes differs from traversal order: scene [2, 0]; node 2 has child 1.
  const std::string rest =
      "\"scene\":0,\"scenes\":[{\"nodes\":[2,0]}],\"nodes\":["
      "{\"name\":\"last\",\"mesh\":1,\"translation\":[0,0,4]},"
      "{\"name\":\"child\",\"mesh\":1,\"translation\":[0,0,-1]},"
      "{\"name\":\"first\",\"mesh\":0,\"translation\":[0,0,1],\"children\":[1]}],"
      "\"meshes\":[{\"primitives\":[" +
      primitive(tri) + "," + primitive(tri_y) +
      "]},"
      "{\"primitives\":[" +
      primitive(tri) + "]}]";
  Scene s = loadJson(b.json(rest));
  ASSERT_EQ(s.triangleCount(), 4u);
  expectNear(s.positions[0], {0, 0, 1});   // node "first", primitive 0
  expectNear(s.positions[3], {0, 10, 1});  // node "first", primitive 1
  expectNear(s.positions[6], {0, 0, 0});   // its child: (0,0,1) + (0,0,-1)
  expectNear(s.positions[9], {0, 0, 4});   // node "last"
}

TEST(GltfLoader, UsesAllRootNodesWhenThereIsNoScene) {
  GltfBuilder b;
  int tri = b.vec3({0, 0, 0, 1, 0, 0, 0, 1, 0});
  const std::string rest =
      "\"nodes\":[{\"children\":[2]},{\"mesh\":0,\"translation\":[0,0,5]},"
      "{\"mesh\":0,\"translation\":[0,0,7]}],\"meshes\":[{\"primitives\":[" +
      primitive(tri) + "]}]";
  Scene s = loadJson(b.json(rest));
  ASSERT_EQ(s.triangleCount(), 2u);
  EXPECT_FLOAT_EQ(s.positions[0].z, 7.0f);  // root 0's child first
  EXPECT_FLOAT_EQ(s.positions[3].z, 5.0f);
}

TEST(GltfLoader, FillsMissingNormalsWithGeometricNormal) {
  GltfBuilder b;
  int tri = b.vec3({0, 0, 0, 1, 0, 0, 0, 1, 0});
  int nrm = b.vec3({1, 0, 0, 1, 0, 0, 1, 0, 0});
  Scene s = loadJson(b.json(singleMesh(primitive(tri, -1, -1, 4, nrm) + "," + primitive(tri))));
  ASSERT_EQ(s.normals.size(), s.positions.size());
  expectNear(s.normals[0], {1, 0, 0});
  expectNear(s.normals[3], {0, 0, 1});
  expectNear(s.normals[5], {0, 0, 1});
}

TEST(GltfLoader, SkipsNonTrianglePrimitivesAndCountsThem) {
  GltfBuilder b;
  int tri = b.vec3({0, 0, 0, 1, 0, 0, 0, 1, 0});
  Scene s = loadJson(b.json(singleMesh(primitive(tri, -1, -1, 1) + "," + primitive(tri) + "," +
                                       primitive(tri, -1, -1, 0))));
  EXPECT_EQ(s.triangleCount(), 1u);
  EXPECT_EQ(s.skipped_primitives, 2u);
  ASSERT_FALSE(s.warnings.empty());
  EXPECT_NE(s.warnings.back().find("2 primitive(s) skipped"), std::string::npos);
}

TEST(GltfLoader, DropsTrianglesWithNanVertexAndCountsThem) {
  GltfBuilder b;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  int pos = b.vec3({0, 0, 0, 1, 0, 0, 0, 1, 0, nan, 0, 0});
  int idx = b.indicesU16({0, 1, 2, 0, 3, 2, 2, 1, 0});
  Scene s = loadJson(b.json(singleMesh(primitive(pos, idx))));
  EXPECT_EQ(s.triangleCount(), 2u);
  EXPECT_EQ(s.dropped_degenerate, 1u);
  EXPECT_EQ(s.material_of.size(), 2u);
  expectNear(s.positions[3], {0, 1, 0});  // the third triangle moved up to second place
  ASSERT_FALSE(s.warnings.empty());
  EXPECT_NE(s.warnings.back().find("1 triangle(s) with NaN/Inf"), std::string::npos);
}

TEST(GltfLoader, DropsZeroAreaTrianglesWithACount) {
  GltfBuilder b;
  // Collinear, a repeated vertex, and one real triangle.
  int pos =
      b.vec3({0, 0, 0, 1, 0, 0, 2, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 1, 0});
  Scene s = loadJson(b.json(singleMesh(primitive(pos))));
  EXPECT_EQ(s.triangleCount(), 1u);
  EXPECT_EQ(s.dropped_zero_area, 2u);
  EXPECT_EQ(s.dropped_degenerate, 0u);
  ASSERT_FALSE(s.warnings.empty());
  EXPECT_NE(s.warnings.back().find("2 triangle(s) with zero area"), std::string::npos);
}

// ---------------------------------------------------------------------------------------------
// Cameras and lights

TEST(GltfLoader, ReadsPerspectiveCameraWithRigidWorldFrame) {
  GltfBuilder b;
  int tri = b.vec3({0, 0, 0, 1, 0, 0, 0, 1, 0});
  // The camera sits under a scaled parent; its frame must come out orthonormal.
  const std::string rest =
      "\"scenes\":[{\"nodes\":[0,1]}],\"nodes\":[{\"mesh\":0},"
      "{\"scale\":[3,3,3],\"children\":[2]},"
      "{\"name\":\"cam_node\",\"camera\":0,\"translation\":[0,0,2],"
      "\"rotation\":[0,0.70710678,0,0.70710678]}],"
      "\"cameras\":[{\"name\":\"main\",\"type\":\"perspective\",\"perspective\":"
      "{\"yfov\":0.5,\"aspectRatio\":1.5,\"znear\":0.1}}],"
      "\"meshes\":[{\"primitives\":[" +
      primitive(tri) + "]}]";
  Scene s = loadJson(b.json(rest));
  ASSERT_TRUE(s.has_camera);
  EXPECT_EQ(s.camera.name, "main");
  EXPECT_FALSE(s.camera.orthographic);
  EXPECT_FLOAT_EQ(s.camera.yfov, 0.5f);
  EXPECT_FLOAT_EQ(s.camera.aspect, 1.5f);
  expectNear(glm::vec3(s.camera.world[3]), {0, 0, 6});   // eye: 3 * (0,0,2)
  expectNear(glm::vec3(s.camera.world[0]), {0, 0, -1});  // +90 deg about Y: x -> -z
  expectNear(glm::vec3(s.camera.world[1]), {0, 1, 0});
  expectNear(glm::vec3(s.camera.world[2]), {1, 0, 0});  // looks down -Z = world -X
  EXPECT_FALSE(s.has_lights);
}

TEST(GltfLoader, ReadsOrthographicCameraWithoutAspect) {
  GltfBuilder b;
  int tri = b.vec3({0, 0, 0, 1, 0, 0, 0, 1, 0});
  const std::string rest =
      "\"scenes\":[{\"nodes\":[0,1]}],\"nodes\":[{\"mesh\":0},{\"camera\":0}],"
      "\"cameras\":[{\"type\":\"orthographic\",\"orthographic\":"
      "{\"xmag\":2,\"ymag\":1.5,\"znear\":0,\"zfar\":10}}],"
      "\"meshes\":[{\"primitives\":[" +
      primitive(tri) + "]}]";
  Scene s = loadJson(b.json(rest));
  ASSERT_TRUE(s.has_camera);
  EXPECT_TRUE(s.camera.orthographic);
  EXPECT_FLOAT_EQ(s.camera.xmag, 2.0f);
  EXPECT_FLOAT_EQ(s.camera.ymag, 1.5f);
  EXPECT_FLOAT_EQ(s.camera.aspect, 0.0f);
}

std::string twoCameraScene(GltfBuilder& b) {
  int tri = b.vec3({0, 0, 0, 1, 0, 0, 0, 1, 0});
  return b.json(
      "\"scenes\":[{\"nodes\":[0,1,2]}],\"nodes\":[{\"mesh\":0},"
      "{\"name\":\"front\",\"camera\":0,\"translation\":[0,0,1]},"
      "{\"name\":\"side\",\"camera\":1,\"translation\":[5,0,0]}],"
      "\"cameras\":[{\"name\":\"cam_a\",\"type\":\"perspective\","
      "\"perspective\":{\"yfov\":0.7,\"znear\":0.1}},"
      "{\"name\":\"cam_b\",\"type\":\"perspective\","
      "\"perspective\":{\"yfov\":0.9,\"znear\":0.1}}],"
      "\"meshes\":[{\"primitives\":[" +
      primitive(tri) + "]}]");
}

TEST(GltfLoader, PicksFirstCameraByDefaultAndNamedCameraOnRequest) {
  GltfBuilder b;
  const std::string json = twoCameraScene(b);
  EXPECT_EQ(loadJson(json).camera.name, "cam_a");
  Scene by_camera = loadJson(json, GltfLoadOptions{"cam_b"});
  EXPECT_EQ(by_camera.camera.name, "cam_b");
  EXPECT_FLOAT_EQ(by_camera.camera.world[3].x, 5.0f);
  EXPECT_EQ(loadJson(json, GltfLoadOptions{"side"}).camera.name, "cam_b");  // by node name
  EXPECT_USAGE_ERROR(loadJson(json, GltfLoadOptions{"top"}),
                     "camera 'top' not found; available: 0 = camera 0 'cam_a' on node 1 "
                     "'front', 1 = camera 1 'cam_b' on node 2 'side'");
}

// Unnamed cameras (common in real files) are chosen by their position in traversal order.
TEST(GltfLoader, PicksACameraByIndex) {
  GltfBuilder b;
  std::string json = twoCameraScene(b);
  for (const char* name :
       {"\"name\":\"cam_a\",", "\"name\":\"cam_b\",", "\"name\":\"front\",", "\"name\":\"side\","})
    json.erase(json.find(name), std::string(name).size());
  EXPECT_FLOAT_EQ(loadJson(json, GltfLoadOptions{"1"}).camera.world[3].x, 5.0f);
  EXPECT_FLOAT_EQ(loadJson(json, GltfLoadOptions{"0"}).camera.world[3].z, 1.0f);
  EXPECT_USAGE_ERROR(loadJson(json, GltfLoadOptions{"2"}),
                     "camera '2' not found; available: 0 = camera 0 on node 1, 1 = camera 1 on "
                     "node 2");
}

TEST(GltfLoader, ReadsPunctualLightsWithWhiteDefaultColor) {
  GltfBuilder b;
  int tri = b.vec3({0, 0, 0, 1, 0, 0, 0, 1, 0});
  const std::string rest =
      "\"extensionsUsed\":[\"KHR_lights_punctual\"],"
      "\"extensions\":{\"KHR_lights_punctual\":{\"lights\":["
      "{\"type\":\"point\"},"
      "{\"type\":\"spot\",\"color\":[1,0.5,0.25],\"intensity\":7,\"range\":20,"
      "\"spot\":{\"innerConeAngle\":0.2,\"outerConeAngle\":0.4}},"
      "{\"type\":\"directional\",\"intensity\":3}]}},"
      "\"scenes\":[{\"nodes\":[0,1,2,3]}],\"nodes\":[{\"mesh\":0},"
      "{\"translation\":[1,2,3],\"extensions\":{\"KHR_lights_punctual\":{\"light\":0}}},"
      // Spot rotated +90 deg about X: local -Z points to world +Y.
      "{\"translation\":[0,-4,0],\"rotation\":[0.70710678,0,0,0.70710678],"
      "\"extensions\":{\"KHR_lights_punctual\":{\"light\":1}}},"
      // Directional rotated +90 deg about Y: local -Z points to world -X.
      "{\"rotation\":[0,0.70710678,0,0.70710678],"
      "\"extensions\":{\"KHR_lights_punctual\":{\"light\":2}}}],"
      "\"meshes\":[{\"primitives\":[" +
      primitive(tri) + "]}]";
  Scene s = loadJson(b.json(rest));
  ASSERT_TRUE(s.has_lights);
  ASSERT_EQ(s.lights.size(), 3u);
  const Light& point = s.lights[0];
  EXPECT_EQ(point.type, LightType::Point);
  expectNear(point.color, {1, 1, 1});
  EXPECT_FLOAT_EQ(point.intensity, 1.0f);
  expectNear(point.position, {1, 2, 3});
  EXPECT_FLOAT_EQ(point.range, 0.0f);

  const Light& spot = s.lights[1];
  EXPECT_EQ(spot.type, LightType::Spot);
  expectNear(spot.color, {1, 0.5f, 0.25f});
  EXPECT_FLOAT_EQ(spot.intensity, 7.0f);
  EXPECT_FLOAT_EQ(spot.range, 20.0f);
  EXPECT_FLOAT_EQ(spot.inner_cone, 0.2f);
  EXPECT_FLOAT_EQ(spot.outer_cone, 0.4f);
  expectNear(spot.position, {0, -4, 0});
  expectNear(spot.direction, {0, 1, 0});

  const Light& sun = s.lights[2];
  EXPECT_EQ(sun.type, LightType::Directional);
  EXPECT_FLOAT_EQ(sun.intensity, 3.0f);
  expectNear(sun.direction, {-1, 0, 0});
}

// ---------------------------------------------------------------------------------------------
// Materials

TEST(GltfLoader, MapsMaterialFactorsAndExtensions) {
  GltfBuilder b;
  int tri = b.vec3({0, 0, 0, 1, 0, 0, 0, 1, 0});
  const std::string materials =
      "\"materials\":[{\"name\":\"glass\",\"doubleSided\":true,\"alphaMode\":\"MASK\","
      "\"alphaCutoff\":0.3,\"pbrMetallicRoughness\":{\"baseColorFactor\":[0.1,0.2,0.3,0.6],"
      "\"metallicFactor\":0.25,"
      "\"roughnessFactor\":0.75},\"emissiveFactor\":[1,0.5,0],"
      "\"extensions\":{\"KHR_materials_transmission\":{\"transmissionFactor\":0.9},"
      "\"KHR_materials_ior\":{\"ior\":1.33},"
      "\"KHR_materials_volume\":{\"attenuationColor\":[0.5,0.6,0.7],\"attenuationDistance\":2},"
      "\"KHR_materials_emissive_strength\":{\"emissiveStrength\":4}}},"
      "{\"name\":\"plain\",\"extensions\":{\"KHR_materials_volume\":{\"thicknessFactor\":1}}}]";
  Scene s = loadJson(b.json(singleMesh(primitive(tri, -1, 1) + "," + primitive(tri) + "," +
                                           primitive(tri, -1, 0) + "," + primitive(tri),
                                       materials)));
  ASSERT_EQ(s.materials.size(), 3u);  // two from the file, one default appended once
  EXPECT_EQ(s.material_of, (std::vector<int>{1, 2, 0, 2}));

  const Material& glass = s.materials[0];
  EXPECT_EQ(glass.name, "glass");
  expectNear(glass.base_color, {0.1f, 0.2f, 0.3f});
  EXPECT_FLOAT_EQ(glass.metallic, 0.25f);
  EXPECT_FLOAT_EQ(glass.roughness, 0.75f);
  EXPECT_FLOAT_EQ(glass.transmission, 0.9f);
  EXPECT_FLOAT_EQ(glass.ior, 1.33f);
  expectNear(glass.attenuation_color, {0.5f, 0.6f, 0.7f});
  EXPECT_FLOAT_EQ(glass.attenuation_distance, 2.0f);
  expectNear(glass.emissive, {4, 2, 0});
  EXPECT_TRUE(glass.double_sided);
  EXPECT_FLOAT_EQ(glass.base_alpha, 0.6f);
  EXPECT_EQ(glass.alpha_mode, AlphaMode::Mask);
  EXPECT_FLOAT_EQ(glass.alpha_cutoff, 0.3f);

  const Material& plain = s.materials[1];  // glTF defaults
  expectNear(plain.base_color, {1, 1, 1});
  EXPECT_FLOAT_EQ(plain.metallic, 1.0f);
  EXPECT_FLOAT_EQ(plain.roughness, 1.0f);
  EXPECT_FLOAT_EQ(plain.transmission, 0.0f);
  EXPECT_FLOAT_EQ(plain.ior, 1.5f);
  EXPECT_FLOAT_EQ(plain.attenuation_distance, 0.0f);  // glTF +infinity: no absorption
  expectNear(plain.emissive, {0, 0, 0});
  EXPECT_FALSE(plain.double_sided);
  EXPECT_FLOAT_EQ(plain.base_alpha, 1.0f);
  EXPECT_EQ(plain.alpha_mode, AlphaMode::Opaque);
  EXPECT_FLOAT_EQ(plain.alpha_cutoff, 0.5f);

  EXPECT_EQ(s.materials[2].name, "default");
}

TEST(GltfLoader, KeepsTextureSlotsAndImagesEncoded) {
  GltfBuilder b;
  int tri = b.vec3({0, 0, 0, 1, 0, 0, 0, 1, 0});
  const std::string extra =
      "\"images\":[{\"uri\":\"data:image/png;base64,iVBORw0KGgo=\"}],"
      "\"textures\":[{\"source\":0}],"
      "\"materials\":[{\"pbrMetallicRoughness\":{\"baseColorTexture\":{\"index\":0}},"
      "\"normalTexture\":{\"index\":0}},{\"normalTexture\":{\"index\":0}}]";
  Scene s =
      loadJson(b.json(singleMesh(primitive(tri, -1, 0) + "," + primitive(tri, -1, 1), extra)));
  EXPECT_EQ(s.materials[0].base_color_texture.texture, 0);
  ASSERT_EQ(s.images.size(), 1u);
  EXPECT_EQ(s.images[0].encoded.size(), 8u);  // the PNG signature, kept encoded
  EXPECT_EQ(s.materials[1].normal_texture.texture, 0);
  EXPECT_TRUE(s.warnings.empty());
}

// ---------------------------------------------------------------------------------------------
// Errors

TEST(GltfLoader, RejectsIndexOutOfRange) {
  GltfBuilder b;
  int pos = b.vec3(kQuad);
  int idx = b.indicesU16({0, 1, 2, 0, 2, 7});
  EXPECT_SCENE_ERROR(loadJson(b.json(singleMesh(primitive(pos, idx)))),
                     "test.gltf: accessor 1: index 7 out of range for 4 vertices");
}

TEST(GltfLoader, RejectsAccessorBeyondItsBuffer) {
  GltfBuilder b;
  // 4 vertices claimed over 3 vertices' worth of bytes.
  int pos = b.addAccessor(bytesOf(std::vector<float>(9, 0.0f)), kFloat, 4, "VEC3");
  EXPECT_SCENE_ERROR(loadJson(b.json(singleMesh(primitive(pos)))),
                     "test.gltf: accessor 0: 4 elements at offset 0 with stride 12 exceed "
                     "bufferView 0 of 36 bytes");
}

TEST(GltfLoader, RejectsStrideSmallerThanElement) {
  GltfBuilder b;
  int pos = b.addAccessor(bytesOf(std::vector<float>(9, 0.0f)), kFloat, 3, "VEC3", 8);
  EXPECT_SCENE_ERROR(loadJson(b.json(singleMesh(primitive(pos)))), "byteStride 8");
}

TEST(GltfLoader, RejectsIndexCountNotMultipleOfThree) {
  GltfBuilder b;
  int pos = b.vec3(kQuad);
  int idx = b.indicesU8({0, 1, 2, 3});
  EXPECT_SCENE_ERROR(loadJson(b.json(singleMesh(primitive(pos, idx)))),
                     "accessor 1: 4 indices is not a multiple of 3");
}

TEST(GltfLoader, RejectsNonFloatPositions) {
  GltfBuilder b;
  int pos = b.addAccessor(bytesOf(std::vector<uint16_t>(9, 0)), kUShort, 3, "VEC3");
  EXPECT_SCENE_ERROR(loadJson(b.json(singleMesh(primitive(pos)))),
                     "accessor 0: POSITION must be FLOAT VEC3, not UNSIGNED_SHORT VEC3");
}

// A sparse accessor: its base (a buffer view, or zeros without one) with the listed
// elements replaced.
std::string sparseAccessor(GltfBuilder& b, int base_view, const std::vector<uint16_t>& indices,
                           const std::vector<float>& values, size_t count) {
  const int index_view = b.addView(bytesOf(indices));
  const int value_view = b.addView(bytesOf(values));
  return std::string("{") +
         (base_view >= 0 ? "\"bufferView\":" + std::to_string(base_view) + "," : "") +
         "\"componentType\":5126,\"count\":" + std::to_string(count) +
         ",\"type\":\"VEC3\",\"sparse\":{\"count\":" + std::to_string(indices.size()) +
         ",\"indices\":{\"bufferView\":" + std::to_string(index_view) +
         ",\"componentType\":5123},\"values\":{\"bufferView\":" + std::to_string(value_view) +
         "}}}";
}

TEST(GltfLoader, SparseAccessorReplacesTheListedElements) {
  GltfBuilder b;
  // The quad with vertex 2 at (5, 5, 0): the sparse values put it back at (1, 1, 0).
  std::vector<float> moved = kQuad;
  moved[6] = moved[7] = 5;
  const int base = b.addView(bytesOf(moved));
  const int pos = b.addRawAccessor(sparseAccessor(b, base, {2}, {1, 1, 0}, 4));
  const int idx = b.indicesU8({0, 1, 2, 0, 2, 3});
  expectQuad(loadJson(b.json(singleMesh(primitive(pos, idx)))));
}

TEST(GltfLoader, SparseAccessorWithoutBufferViewStartsFromZeros) {
  GltfBuilder b;
  // Vertex 0 is the origin by default; the other three come from the sparse values.
  const int pos =
      b.addRawAccessor(sparseAccessor(b, -1, {1, 2, 3}, {1, 0, 0, 1, 1, 0, 0, 1, 0}, 4));
  const int idx = b.indicesU8({0, 1, 2, 0, 2, 3});
  expectQuad(loadJson(b.json(singleMesh(primitive(pos, idx)))));
}

TEST(GltfLoader, RejectsSparseIndicesThatDoNotIncrease) {
  GltfBuilder b;
  const int base = b.addView(bytesOf(kQuad));
  const int pos = b.addRawAccessor(sparseAccessor(b, base, {2, 1}, {1, 1, 0, 1, 0, 0}, 4));
  const int idx = b.indicesU8({0, 1, 2, 0, 2, 3});
  EXPECT_SCENE_ERROR(loadJson(b.json(singleMesh(primitive(pos, idx)))),
                     "accessor 0: sparse index 1 does not increase");
}

TEST(GltfLoader, RejectsSparseIndexOutOfRange) {
  GltfBuilder b;
  const int base = b.addView(bytesOf(kQuad));
  const int pos = b.addRawAccessor(sparseAccessor(b, base, {4}, {1, 1, 0}, 4));
  EXPECT_SCENE_ERROR(loadJson(b.json(singleMesh(primitive(pos)))),
                     "sparse index 4 out of range for 4 elements");
}

// KHR_mesh_quantization: integer positions, normalized (c / 32767 for SHORT) or not.
TEST(GltfLoader, QuantizedPositionsAreDecodedAsTheSpecificationSays) {
  GltfBuilder b;
  const std::vector<int16_t> normalized = {0, 0, 0, 32767, 0, 0, 32767, 32767, 0, 0, 32767, 0};
  const int pos = b.addAccessor(bytesOf(normalized), 5122, 4, "VEC3", 0, 0, ",\"normalized\":true");
  const std::vector<uint8_t> plain = {0, 0, 0, 2, 0, 0, 2, 2, 0, 0, 2, 0};
  const int pos2 = b.addAccessor(bytesOf(plain), kUByte, 4, "VEC3");
  const int idx = b.indicesU8({0, 1, 2, 0, 2, 3});
  const std::string rest =
      "\"extensionsUsed\":[\"KHR_mesh_quantization\"],"
      "\"extensionsRequired\":[\"KHR_mesh_quantization\"]," +
      singleMesh(primitive(pos, idx) + "," + primitive(pos2, idx));
  const Scene scene = loadJson(b.json(rest));
  ASSERT_EQ(scene.triangleCount(), 4u);
  for (size_t i = 0; i < 6; ++i) {
    EXPECT_EQ(scene.positions[i], kQuadTriangles[i]);  // 32767 / 32767 is exactly 1
    EXPECT_EQ(scene.positions[6 + i], 2.0f * kQuadTriangles[i]);
  }
}

TEST(GltfLoader, IntegerPositionsWithoutQuantizationExtensionNameIt) {
  GltfBuilder b;
  const int pos = b.addAccessor(bytesOf(std::vector<uint16_t>(9, 0)), kUShort, 3, "VEC3");
  EXPECT_SCENE_ERROR(loadJson(b.json(singleMesh(primitive(pos)))), "KHR_mesh_quantization");
}

// Draco and meshopt files are read (gltf_draco_test.cpp, gltf_meshopt_test.cpp); an
// extension the loader does not know is named.
TEST(GltfLoader, UnknownRequiredExtensionsAreNamed) {
  const std::string ext = "EXT_mesh_gpu_instancing";
  const std::string json =
      "{\"asset\":{\"version\":\"2.0\"},\"extensionsUsed\":[\"" + ext +
      "\"],\"extensionsRequired\":[\"" + ext +
      "\"],\"accessors\":[{\"componentType\":5125,\"count\":3,\"type\":\"SCALAR\"},"
      "{\"componentType\":5126,\"count\":3,\"type\":\"VEC3\"}],"
      "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":1},\"indices\":0}]}],"
      "\"nodes\":[{\"mesh\":0}],\"scenes\":[{\"nodes\":[0]}]}";
  EXPECT_SCENE_ERROR(loadJson(json), "requires extension " + ext + ", which is not supported");
}

// Morph targets at the still pose: base + sum of weight * displacement, the node's weights
// before the mesh's.
TEST(GltfLoader, MorphTargetsAtTheirDefaultWeights) {
  GltfBuilder b;
  const int pos = b.vec3({0, 0, 0, 1, 0, 0, 0, 1, 0});
  const int d0 = b.vec3({0, 0, 2, 0, 0, 0, 0, 0, 0});  // moves vertex 0 along +z
  const int d1 = b.vec3({0, 0, 0, 4, 0, 0, 0, 0, 0});  // moves vertex 1 along +x
  const std::string prim = "{\"attributes\":{\"POSITION\":" + std::to_string(pos) +
                           "},\"targets\":[{\"POSITION\":" + std::to_string(d0) +
                           "},{\"POSITION\":" + std::to_string(d1) + "}]}";
  auto doc = [&](const std::string& node_weights) {
    return b.json("\"scenes\":[{\"nodes\":[0]}],\"nodes\":[{\"mesh\":0" + node_weights +
                  "}],\"meshes\":[{\"primitives\":[" + prim + "],\"weights\":[0.5,0.25]}]");
  };
  const Scene mesh_weights = loadJson(doc(""));
  ASSERT_EQ(mesh_weights.triangleCount(), 1u);
  EXPECT_EQ(mesh_weights.positions[0], glm::vec3(0, 0, 1));  // 0.5 * 2
  EXPECT_EQ(mesh_weights.positions[1], glm::vec3(2, 0, 0));  // 1 + 0.25 * 4
  EXPECT_EQ(mesh_weights.positions[2], glm::vec3(0, 1, 0));
  const Scene node_weights = loadJson(doc(",\"weights\":[0,1]"));
  EXPECT_EQ(node_weights.positions[0], glm::vec3(0, 0, 0));
  EXPECT_EQ(node_weights.positions[1], glm::vec3(5, 0, 0));
}

// A skinned triangle: vertex 0 bound to joint 0 (translated by (0, 0, 3)), vertex 1 to
// joint 1 (rotated 90 degrees about +z at the origin, inverse bind matrix a translation by
// (-1, 0, 0)), vertex 2 half to each with weights that sum to 0.5 (normalised to 1). The
// mesh node's own translation by (100, 0, 0) must not apply.
TEST(GltfLoader, SkinnedMeshFollowsItsJoints) {
  GltfBuilder b;
  const int pos = b.vec3({0, 0, 0, 1, 0, 0, 1, 1, 0});
  const std::vector<uint8_t> joints = {0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0};
  const int j = b.addAccessor(bytesOf(joints), kUByte, 3, "VEC4");
  const int w = b.addAccessor(
      bytesOf(std::vector<float>{1, 0, 0, 0, 1, 0, 0, 0, 0.25f, 0.25f, 0, 0}), kFloat, 3, "VEC4");
  std::vector<float> ibm(32, 0.0f);
  for (int m = 0; m < 2; ++m)
    for (int d = 0; d < 4; ++d) ibm[size_t(m * 16 + d * 5)] = 1.0f;
  ibm[16 + 12] = -1.0f;  // joint 1: translation column x = -1
  const int inverse_bind = b.addAccessor(bytesOf(ibm), kFloat, 2, "MAT4");
  const std::string rest =
      "\"scenes\":[{\"nodes\":[0,1,2]}],\"nodes\":[{\"mesh\":0,\"skin\":0,"
      "\"translation\":[100,0,0]},{\"translation\":[0,0,3]},"
      "{\"rotation\":[0,0,0.7071067811865476,0.7071067811865476]}],"
      "\"skins\":[{\"joints\":[1,2],\"inverseBindMatrices\":" +
      std::to_string(inverse_bind) + "}],\"meshes\":[{\"primitives\":[{\"attributes\":{" +
      "\"POSITION\":" + std::to_string(pos) + ",\"JOINTS_0\":" + std::to_string(j) +
      ",\"WEIGHTS_0\":" + std::to_string(w) + "}}]}]";
  const Scene scene = loadJson(b.json(rest));
  ASSERT_EQ(scene.triangleCount(), 1u);
  expectNear(scene.positions[0], {0, 0, 3});  // (0,0,0) + (0,0,3)
  expectNear(scene.positions[1], {0, 0, 0});  // (1,0,0) - (1,0,0), rotated
  // (1,1,0): joint 0 gives (1,1,3); joint 1 gives rot((0,1,0)) = (-1,0,0); half each.
  expectNear(scene.positions[2], {0, 0.5f, 1.5f});
}

TEST(GltfLoader, ReadsVertexColours) {
  GltfBuilder b;
  const int pos = b.vec3({0, 0, 0, 1, 0, 0, 0, 1, 0});
  const int colour = b.vec3({1, 0, 0, 0, 1, 0, 0, 0, 1});
  const std::string prim = "{\"attributes\":{\"POSITION\":" + std::to_string(pos) +
                           ",\"COLOR_0\":" + std::to_string(colour) + "}}";
  const Scene scene = loadJson(b.json(singleMesh(prim)));
  ASSERT_EQ(scene.triangleCount(), 1u);
  EXPECT_EQ(scene.colors, (std::vector<glm::vec4>{{1, 0, 0, 1}, {0, 1, 0, 1}, {0, 0, 1, 1}}));
  EXPECT_TRUE(scene.warnings.empty());
}

// A mesh large enough to be read and moved to world space on all cores (more vertices than
// the parallel read's threshold, many chunks of triangles), under a mirroring node, with
// NaN and zero-area triangles spread through it and a colour per vertex: the kept
// triangles come out in order, wound back, their colours with them, and the dropped ones
// are counted, as when the triangles went one at a time.
TEST(GltfLoader, AManyTriangleMeshIsReadInOrderOnAllCores) {
  constexpr size_t kTriangles = 30000;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  auto dropsNan = [](size_t t) { return t % 997 == 5; };
  auto dropsArea = [](size_t t) { return t % 1009 == 7; };
  std::vector<float> xyz, rgb;
  for (size_t t = 0; t < kTriangles; ++t) {
    const float x = float(t);
    const float corners[9] = {
        x, 0, 0, x, 1, 0, x, dropsArea(t) ? 1.0f : 0.0f, dropsArea(t) ? 0.0f : 1.0f};
    xyz.insert(xyz.end(), corners, corners + 9);
    if (dropsNan(t)) xyz[xyz.size() - 2] = nan;
    for (int k = 0; k < 3; ++k) {
      const float v = float(3 * t + size_t(k));
      rgb.insert(rgb.end(), {v / float(3 * kTriangles), 0.5f, 1.0f - v / float(3 * kTriangles)});
    }
  }
  GltfBuilder b;
  const int pos = b.vec3(xyz);
  const int colour = b.vec3(rgb);
  std::vector<float> x_axis(xyz.size(), 0.0f);
  for (size_t v = 0; v < x_axis.size(); v += 3) x_axis[v] = 1.0f;
  const int normal = b.vec3(x_axis);
  const std::string rest =
      "\"scenes\":[{\"nodes\":[0]}],\"nodes\":[{\"mesh\":0,\"scale\":[-1,1,1],"
      "\"translation\":[0,0,2]}],\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":" +
      std::to_string(pos) + ",\"NORMAL\":" + std::to_string(normal) +
      ",\"COLOR_0\":" + std::to_string(colour) + "}}]}]";
  // As a .gltf (a data URI) and as a .glb whose binary chunk (3 MB) is set aside
  // (gltf_compressed_input.h).
  const std::string glb = b.glb(rest);
  ASSERT_GE(b.bin().size(), gltf::kSetAsideBinaryBytes);
  for (const Scene& s : {loadJson(b.json(rest)),
                         loadGltfFromMemory(reinterpret_cast<const unsigned char*>(glb.data()),
                                            glb.size(), "", "many.glb")}) {
    size_t kept = 0, nans = 0, flat = 0;
    for (size_t t = 0; t < kTriangles; ++t) {
      if (dropsNan(t)) {
        ++nans;
        continue;
      }
      if (dropsArea(t)) {
        ++flat;
        continue;
      }
      ASSERT_LT(kept, s.triangleCount());
      // Mirrored by the node: corners 1 and 2 swap places.
      const size_t from[3] = {3 * t, 3 * t + 2, 3 * t + 1};
      for (int k = 0; k < 3; ++k) {
        const size_t v = from[k];
        const glm::vec3 want(-xyz[3 * v], xyz[3 * v + 1], xyz[3 * v + 2] + 2.0f);
        ASSERT_EQ(s.positions[3 * kept + size_t(k)], want) << "triangle " << t;
        ASSERT_EQ(s.normals[3 * kept + size_t(k)], glm::vec3(-1, 0, 0)) << "triangle " << t;
        ASSERT_EQ(s.colors[3 * kept + size_t(k)],
                  glm::vec4(rgb[3 * v], rgb[3 * v + 1], rgb[3 * v + 2], 1.0f))
            << "triangle " << t;
      }
      ++kept;
    }
    EXPECT_EQ(s.triangleCount(), kept);
    EXPECT_EQ(s.colors.size(), 3 * kept);
    EXPECT_EQ(s.normals.size(), 3 * kept);
    EXPECT_EQ(s.dropped_degenerate, nans);
    EXPECT_EQ(s.dropped_zero_area, flat);
  }
}

// A large .glb's binary chunk is set aside from what tinygltf parses (no binary chunk in
// its bytes, buffer 0 a one-byte placeholder) and put back as buffer 0 after; not when an
// image reads a buffer view, when the chunk is small, or when buffer 0 has a uri or is
// longer than the chunk (tinygltf then says why).
TEST(GltfLoader, ALargeGlbsBinaryChunkIsSetAsideWhileTinygltfParses) {
  const std::string bin(gltf::kSetAsideBinaryBytes, '\x5a');
  auto glbOf = [&](const std::string& buffer, const std::string& more, const std::string& data) {
    return makeGlb("{\"asset\":{\"version\":\"2.0\"},\"buffers\":[" + buffer + "]" + more + "}",
                   data);
  };
  auto prepared = [](const std::string& glb) {
    const auto* data = reinterpret_cast<const unsigned char*>(glb.data());
    uint32_t json_length = 0;
    std::memcpy(&json_length, glb.data() + 12, 4);
    const std::string_view json(glb.data() + 20, json_length);
    return gltf::prepareCompressedInput(nlohmann::json::parse(json), data, glb.size(), true);
  };
  const std::string length = "{\"byteLength\":" + std::to_string(bin.size() - 8) + "}";
  const std::string plain = glbOf(length, "", bin);
  const gltf::CompressedInput input = prepared(plain);
  ASSERT_NE(input.glb_binary, nullptr);
  EXPECT_EQ(input.glb_binary,
            reinterpret_cast<const unsigned char*>(plain.data()) + plain.size() - bin.size());
  EXPECT_EQ(input.glb_binary_bytes, bin.size() - 8);
  EXPECT_LT(input.bytes.size(), 1000u);  // header and JSON only
  tinygltf::Model model;
  model.buffers.resize(1);
  model.buffers[0].data = {0};
  model.buffers[0].uri = "data:application/octet-stream;base64,AA==";
  gltf::restoreCompressedInput(input, model);
  EXPECT_EQ(model.buffers[0].data, std::vector<unsigned char>(bin.size() - 8, 0x5a));
  EXPECT_TRUE(model.buffers[0].uri.empty());

  const std::string image = ",\"images\":[{\"bufferView\":0,\"mimeType\":\"image/png\"}]";
  EXPECT_EQ(prepared(glbOf(length, image, bin)).glb_binary, nullptr);
  EXPECT_EQ(prepared(glbOf(length, "", bin.substr(0, bin.size() / 2))).glb_binary, nullptr);
  EXPECT_EQ(prepared(glbOf("{\"byteLength\":8,\"uri\":\"x.bin\"}", "", bin)).glb_binary, nullptr);
  EXPECT_EQ(prepared(glbOf("{\"byteLength\":" + std::to_string(bin.size() + 4) + "}", "", bin))
                .glb_binary,
            nullptr);
}

// Indices are checked on all cores: of several out of range, the first is reported.
TEST(GltfLoader, OfManyIndicesOutOfRangeTheFirstIsReported) {
  GltfBuilder b;
  const int pos = b.vec3(kQuad);
  std::vector<uint32_t> indices(90000);
  for (size_t i = 0; i < indices.size(); ++i) indices[i] = uint32_t(i % 4);
  indices[40001] = 99999991;  // the first
  indices[50002] = 99999992;
  indices[89999] = 99999993;
  const int idx = b.indicesU32(indices);
  EXPECT_SCENE_ERROR(loadJson(b.json(singleMesh(primitive(pos, idx)))),
                     "accessor 1: index 99999991 out of range for 4 vertices");
}

TEST(GltfLoader, RejectsSkinJointOutOfRange) {
  GltfBuilder b;
  const int pos = b.vec3({0, 0, 0, 1, 0, 0, 1, 1, 0});
  const int j = b.addAccessor(bytesOf(std::vector<uint8_t>{0, 0, 0, 0, 7, 0, 0, 0, 0, 0, 0, 0}),
                              kUByte, 3, "VEC4");
  const int w = b.addAccessor(bytesOf(std::vector<float>{1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0}),
                              kFloat, 3, "VEC4");
  const std::string rest =
      "\"scenes\":[{\"nodes\":[0,1]}],\"nodes\":[{\"mesh\":0,\"skin\":0},{}],"
      "\"skins\":[{\"joints\":[1]}],\"meshes\":[{\"primitives\":[{\"attributes\":{"
      "\"POSITION\":" +
      std::to_string(pos) + ",\"JOINTS_0\":" + std::to_string(j) +
      ",\"WEIGHTS_0\":" + std::to_string(w) + "}}]}]";
  EXPECT_SCENE_ERROR(loadJson(b.json(rest)), "vertex 1: JOINTS_0 names joint 7 of 1");
}

TEST(GltfLoader, RejectsNodeCycle) {
  GltfBuilder b;
  int tri = b.vec3({0, 0, 0, 1, 0, 0, 0, 1, 0});
  const std::string rest =
      "\"scenes\":[{\"nodes\":[0]}],\"nodes\":[{\"mesh\":0,\"children\":[1]},"
      "{\"children\":[0]}],\"meshes\":[{\"primitives\":[" +
      primitive(tri) + "]}]";
  EXPECT_SCENE_ERROR(loadJson(b.json(rest)), "node 0: the node hierarchy has a cycle");
}

TEST(GltfLoader, KeepsMessagesOnOneLineDespiteControlCharactersInNames) {
  GltfBuilder b;
  int tri = b.vec3({0, 0, 0, 1, 0, 0, 0, 1, 0});
  const std::string rest =
      "\"scenes\":[{\"nodes\":[0]}],\"nodes\":[{\"name\":\"evil\\nname\\u001b\",\"mesh\":0,"
      "\"children\":[0]}],\"meshes\":[{\"primitives\":[" +
      primitive(tri) + "]}]";
  EXPECT_SCENE_ERROR(loadJson(b.json(rest)),
                     "node 0 'evil; name?': the node hierarchy has a cycle");
}

TEST(GltfLoader, RejectsDanglingIndices) {
  GltfBuilder b;
  int tri = b.vec3({0, 0, 0, 1, 0, 0, 0, 1, 0});
  EXPECT_SCENE_ERROR(
      loadJson(b.json("\"scenes\":[{\"nodes\":[0]}],\"nodes\":[{\"mesh\":3}],\"meshes\":[]")),
      "node 0: mesh 3 does not exist");
  EXPECT_SCENE_ERROR(loadJson(b.json(singleMesh(primitive(tri, -1, 2)))),
                     "mesh 0 primitive 0: material 2 does not exist");
  EXPECT_SCENE_ERROR(loadJson(b.json("\"scenes\":[{\"nodes\":[4]}],\"nodes\":[]")),
                     "node 4 does not exist");
}

TEST(GltfLoader, RejectsSceneWithoutTriangles) {
  const std::string rest =
      "\"scenes\":[{\"nodes\":[0]}],\"nodes\":[{\"camera\":0}],\"cameras\":[{\"type\":"
      "\"perspective\",\"perspective\":{\"yfov\":1,\"znear\":0.1}}]";
  EXPECT_SCENE_ERROR(loadJson(GltfBuilder().json(rest)), "test.gltf: the scene has no triangles");
}

TEST(GltfLoader, RejectsJsonSyntaxError) {
  const std::string message =
      errorOf<SceneError>([] { loadJson("{\"asset\": {\"version\": \"2.0\"},"); });
  EXPECT_EQ(message.rfind("test.gltf: malformed glTF: ", 0), 0u) << message;
  EXPECT_EQ(message.find('\n'), std::string::npos) << message;
}

TEST(GltfLoader, RejectsAbsurdJsonNesting) {
  const std::string json =
      "{\"asset\":{\"version\":\"2.0\"},\"extras\":" + std::string(100000, '[') +
      std::string(100000, ']') + "}";
  EXPECT_SCENE_ERROR(loadJson(json), "JSON nested deeper than");
}

TEST(GltfLoader, RejectsMissingFile) {
  const std::string path = test::tempPath("does_not_exist.glb");
  EXPECT_SCENE_ERROR(loadGltfFile(path), "cannot open scene '" + path + "': ");
}

TEST(GltfLoader, RejectsGlbWithWrongMagic) {
  std::string glb = readFile(test::modelScene("bunny_res4.glb"));
  ASSERT_GT(glb.size(), 20u);
  glb[3] = 'X';
  const std::string path = test::tempPath("wrong_magic.glb");
  writeFile(path, glb);
  EXPECT_SCENE_ERROR(loadGltfFile(path), path + ": not a binary glTF");
}

TEST(GltfLoader, RejectsTruncatedGlb) {
  const std::string glb = readFile(test::modelScene("loader_test.glb"));
  ASSERT_GT(glb.size(), 1000u);
  for (size_t size : {size_t(10), size_t(100), glb.size() / 2, glb.size() - 4}) {
    SCOPED_TRACE("truncated to " + std::to_string(size) + " bytes");
    const std::string path = test::tempPath("truncated.glb");
    writeFile(path, glb.substr(0, size));
    EXPECT_SCENE_ERROR(loadGltfFile(path), path + ": malformed glTF");
  }
}

TEST(GltfLoader, LoadsGlbFromMemoryByMagic) {
  GltfBuilder b;
  int pos = b.vec3(kQuad);
  int idx = b.indicesU8({0, 1, 2, 0, 2, 3});
  const std::string json = "{\"asset\":{\"version\":\"2.0\"},\"buffers\":[{\"byteLength\":" +
                           std::to_string(b.bin().size()) + "}]," + b.viewsAndAccessors() + "," +
                           singleMesh(primitive(pos, idx)) + "}";
  const std::string glb = makeGlb(json, b.bin());
  expectQuad(loadGltfFromMemory(reinterpret_cast<const unsigned char*>(glb.data()), glb.size(), "",
                                "memory.glb"));
}

// ---------------------------------------------------------------------------------------------
// External files

// A folder with scene.gltf whose buffer URI is `uri`, and a valid triangle buffer both inside
// (inside.bin) and next to the folder (outside.bin).
std::string sceneWithBufferUri(const std::string& name, const std::string& uri) {
  namespace fs = std::filesystem;
  const fs::path root = test::tempPath(name);
  fs::create_directories(root / "scene");
  const std::string bin = bytesOf(std::vector<float>{0, 0, 0, 1, 0, 0, 0, 1, 0});
  writeFile((root / "outside.bin").string(), bin);
  writeFile((root / "scene" / "inside.bin").string(), bin);
  const std::string json =
      "{\"asset\":{\"version\":\"2.0\"},\"buffers\":[{\"byteLength\":36,\"uri\":\"" + uri +
      "\"}],\"bufferViews\":[{\"buffer\":0,\"byteLength\":36}],\"accessors\":[{\"bufferView\":0,"
      "\"componentType\":5126,\"count\":3,\"type\":\"VEC3\"}]," +
      singleMesh(primitive(0)) + "}";
  const std::string path = (root / "scene" / "scene.gltf").string();
  writeFile(path, json);
  return path;
}

TEST(GltfLoader, ReadsExternalBufferInsideSceneFolder) {
  EXPECT_EQ(loadGltfFile(sceneWithBufferUri("ext_ok", "inside.bin")).triangleCount(), 1u);
}

TEST(GltfLoader, RejectsExternalUrisLeavingSceneFolder) {
  EXPECT_SCENE_ERROR(loadGltfFile(sceneWithBufferUri("ext_dotdot", "../outside.bin")),
                     "external URI '../outside.bin' contains '..'");
  EXPECT_SCENE_ERROR(loadGltfFile(sceneWithBufferUri("ext_encoded", "%2E%2E/outside.bin")),
                     "external URI '../outside.bin' contains '..'");
  EXPECT_SCENE_ERROR(loadGltfFile(sceneWithBufferUri("ext_abs", "/etc/passwd")),
                     "external URI '/etc/passwd' is an absolute path");
}

TEST(GltfLoader, RejectsSymlinkLeavingSceneFolder) {
  namespace fs = std::filesystem;
  const std::string path = sceneWithBufferUri("ext_link", "link.bin");
  const fs::path dir = fs::path(path).parent_path();
  fs::create_symlink(dir.parent_path() / "outside.bin", dir / "link.bin");
  EXPECT_SCENE_ERROR(loadGltfFile(path), "external URI 'link.bin' leads outside the scene folder");
}

TEST(GltfLoader, RefusesExternalFilesWithoutBaseFolder) {
  const std::string json = readFile(sceneWithBufferUri("ext_nobase", "inside.bin"));
  EXPECT_SCENE_ERROR(loadJson(json), "external URI 'inside.bin' cannot be read");
}

// ---------------------------------------------------------------------------------------------
// Shared scenes

TEST(GltfLoader, LoadsSharedLoaderTestScene) {
  Scene s = loadGltfFile(test::modelScene("loader_test.glb"));
  EXPECT_EQ(s.triangleCount(), 974u);
  EXPECT_EQ(s.material_of.size(), 974u);
  EXPECT_TRUE(s.normals.empty());
  EXPECT_EQ(s.skipped_primitives, 0u);
  EXPECT_EQ(s.dropped_degenerate, 0u);
  ASSERT_TRUE(s.has_camera);
  EXPECT_EQ(s.camera.name, "camera");
  EXPECT_NEAR(s.camera.yfov, 0.6981317f, 1e-6f);
  expectNear(glm::vec3(s.camera.world[3]), {1.881f, 0.6f, 5.168f}, 1e-3f);
  ASSERT_EQ(s.lights.size(), 1u);
  expectNear(s.lights[0].position, {1, 4, 5});
  EXPECT_FLOAT_EQ(s.lights[0].intensity, 40.0f);
  // Order: bunny (948, material "default"), cube_a (12), cube_b (12), triangle (2, "red").
  EXPECT_EQ(s.materials[size_t(s.material_of[0])].name, "default");
  EXPECT_EQ(s.materials[size_t(s.material_of[948])].name, "red");  // cube primitive 0
  EXPECT_EQ(s.materials[size_t(s.material_of[973])].name, "red");  // the triangle
}

TEST(GltfLoader, LoadsSharedBunnyAndOrientationTest) {
  Scene bunny = loadGltfFile(test::modelScene("bunny_res4.glb"));
  EXPECT_EQ(bunny.triangleCount(), 948u);
  Scene orientation = loadGltfFile(test::modelScene("OrientationTest.glb"));
  EXPECT_EQ(orientation.triangleCount(), 524u);
  EXPECT_EQ(orientation.normals.size(), orientation.positions.size());
  // SOURCES.md: bounds (-5.331, ...) .. (5.331, ...).
  glm::vec3 lo(1e30f), hi(-1e30f);
  for (const auto& p : orientation.positions) lo = glm::min(lo, p), hi = glm::max(hi, p);
  expectNear(lo, glm::vec3(-5.331f), 1e-3f);
  expectNear(hi, glm::vec3(5.331f), 1e-3f);
}

}  // namespace
}  // namespace gridrt
