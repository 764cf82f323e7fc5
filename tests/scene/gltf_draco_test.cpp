// KHR_draco_mesh_compression: meshes compressed here with Draco's own encoder, wrapped in
// small glTF documents, loaded, and compared with the same mesh stored uncompressed.
#include <draco/compression/encode.h>
#include <draco/mesh/mesh.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "errors.h"
#include "gltf_document_builder.h"
#include "gltf_loader.h"

namespace gridrt {
namespace {

using test::bytesOf;
using test::GltfDocumentBuilder;

constexpr int kUByte = 5121, kUShort = 5123, kFloat = 5126;

// A slanted box: 8 vertices with unit normals and RGBA colours, 12 triangles.
struct TestMesh {
  std::vector<float> positions = {0.1f,  -1.7f, 3.25f, 2.6f,  -1.2f, 3.0f,  2.9f,  1.3f,
                                  2.5f,  0.35f, 0.8f,  2.75f, -0.2f, -1.5f, 5.5f,  2.3f,
                                  -1.1f, 5.2f,  2.65f, 1.45f, 4.8f,  0.05f, 1.05f, 5.0f};
  std::vector<float> normals;
  std::vector<uint8_t> colors;
  std::vector<uint16_t> indices = {0, 2, 1, 0, 3, 2, 4, 5, 6, 4, 6, 7, 0, 1, 5, 0, 5, 4,
                                   1, 2, 6, 1, 6, 5, 2, 3, 7, 2, 7, 6, 3, 0, 4, 3, 4, 7};
  std::vector<float> texcoords;  // stored uncompressed beside the Draco data
  TestMesh() {
    for (size_t v = 0; v < 8; ++v) {
      const glm::vec3 p(positions[3 * v], positions[3 * v + 1], positions[3 * v + 2]);
      const glm::vec3 n = glm::normalize(p - glm::vec3(1.3f, -0.2f, 3.9f));
      normals.insert(normals.end(), {n.x, n.y, n.z});
      colors.insert(colors.end(), {uint8_t(30 * v), uint8_t(255 - 20 * v), uint8_t(7 + v), 255});
      texcoords.insert(texcoords.end(), {0.125f * float(v), 1.0f - 0.0625f * float(v)});
    }
  }
  size_t vertexCount() const { return positions.size() / 3; }
};

// Draco attribute ids, deliberately not 0, 1, 2: the loader must follow the extension's map.
constexpr uint32_t kPositionId = 7, kNormalId = 3, kColorId = 5;

template <typename T>
void addDracoAttribute(draco::Mesh& mesh, draco::GeometryAttribute::Type type, int components,
                       draco::DataType data_type, bool normalized, const std::vector<T>& values,
                       uint32_t unique_id) {
  draco::GeometryAttribute attribute;
  attribute.Init(type, nullptr, uint8_t(components), data_type, normalized,
                 int64_t(sizeof(T)) * components, 0);
  const int id = mesh.AddAttribute(attribute, true, mesh.num_points());
  for (uint32_t v = 0; v < mesh.num_points(); ++v)
    mesh.attribute(id)->SetAttributeValue(draco::AttributeValueIndex(v),
                                          values.data() + size_t(v) * size_t(components));
  mesh.attribute(id)->set_unique_id(unique_id);
}

// `m` compressed by Draco's encoder: `method` MESH_EDGEBREAKER_ENCODING (reorders the
// triangles and vertices) or MESH_SEQUENTIAL_ENCODING (keeps their order); positions
// quantised to `position_bits`, or stored exactly with 0.
std::string encodeDraco(const TestMesh& m, int method, int position_bits = 0) {
  draco::Mesh mesh;
  mesh.set_num_points(uint32_t(m.vertexCount()));
  for (size_t t = 0; t < m.indices.size(); t += 3)
    mesh.AddFace({draco::PointIndex(m.indices[t]), draco::PointIndex(m.indices[t + 1]),
                  draco::PointIndex(m.indices[t + 2])});
  addDracoAttribute(mesh, draco::GeometryAttribute::POSITION, 3, draco::DT_FLOAT32, false,
                    m.positions, kPositionId);
  addDracoAttribute(mesh, draco::GeometryAttribute::NORMAL, 3, draco::DT_FLOAT32, false, m.normals,
                    kNormalId);
  addDracoAttribute(mesh, draco::GeometryAttribute::COLOR, 4, draco::DT_UINT8, true, m.colors,
                    kColorId);
  draco::Encoder encoder;
  encoder.SetEncodingMethod(method);
  if (position_bits > 0)
    encoder.SetAttributeQuantization(draco::GeometryAttribute::POSITION, position_bits);
  draco::EncoderBuffer buffer;
  const draco::Status status = encoder.EncodeMeshToBuffer(mesh, &buffer);
  EXPECT_TRUE(status.ok()) << status.error_msg_string();
  return std::string(buffer.data(), buffer.size());
}

const std::string kScene = "\"scene\":0,\"scenes\":[{\"nodes\":[0]}],\"nodes\":[{\"mesh\":0}]";

// The primitive as the uncompressed twin stores it.
std::string plainDocument(const TestMesh& m) {
  GltfDocumentBuilder b;
  const int pos = b.floats(m.positions, "VEC3"), nrm = b.floats(m.normals, "VEC3");
  const int col = b.addAccessor(bytesOf(m.colors), kUByte, 8, "VEC4", ",\"normalized\":true");
  const int idx = b.addAccessor(bytesOf(m.indices), kUShort, m.indices.size(), "SCALAR");
  const int uv = b.addAccessor(bytesOf(m.texcoords), kFloat, 8, "VEC2");
  return b.json(kScene + ",\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":" +
                std::to_string(pos) + ",\"NORMAL\":" + std::to_string(nrm) +
                ",\"COLOR_0\":" + std::to_string(col) + ",\"TEXCOORD_0\":" + std::to_string(uv) +
                "},\"indices\":" + std::to_string(idx) + "}]}]");
}

// What a file's Draco primitive may get wrong, for the error tests.
struct DracoDocumentOptions {
  size_t position_count = 8;
  uint32_t normal_id = kNormalId;
  bool with_texcoords = false;  // an uncompressed TEXCOORD_0 (only right for sequential data)
};

// The primitive compressed: accessors without buffer views, the Draco bytes in a view.
GltfDocumentBuilder dracoBuilder(const TestMesh& m, const std::string& draco, std::string& rest,
                                 const DracoDocumentOptions& o = {}) {
  GltfDocumentBuilder b;
  const int view = b.addView(draco);
  auto accessor = [&](int component, size_t count, const char* type, const char* extra = "") {
    return std::to_string(b.addRawAccessor("{\"componentType\":" + std::to_string(component) +
                                           ",\"count\":" + std::to_string(count) + ",\"type\":\"" +
                                           type + "\"" + extra + "}"));
  };
  const std::string pos = accessor(kFloat, o.position_count, "VEC3");
  const std::string nrm = accessor(kFloat, 8, "VEC3");
  const std::string col = accessor(kUByte, 8, "VEC4", ",\"normalized\":true");
  const std::string idx = accessor(kUShort, m.indices.size(), "SCALAR");
  const std::string uv =
      o.with_texcoords ? ",\"TEXCOORD_0\":" +
                             std::to_string(b.addAccessor(bytesOf(m.texcoords), kFloat, 8, "VEC2"))
                       : "";
  rest =
      "\"extensionsUsed\":[\"KHR_draco_mesh_compression\"],"
      "\"extensionsRequired\":[\"KHR_draco_mesh_compression\"]," +
      kScene + ",\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":" + pos +
      ",\"NORMAL\":" + nrm + ",\"COLOR_0\":" + col + uv + "},\"indices\":" + idx +
      ",\"mode\":4,\"extensions\":{\"KHR_draco_mesh_compression\":{\"bufferView\":" +
      std::to_string(view) + ",\"attributes\":{\"POSITION\":" + std::to_string(kPositionId) +
      ",\"NORMAL\":" + std::to_string(o.normal_id) + ",\"COLOR_0\":" + std::to_string(kColorId) +
      "}}}}]}]";
  return b;
}

std::string dracoDocument(const TestMesh& m, const std::string& draco,
                          const DracoDocumentOptions& o = {}) {
  std::string rest;
  const GltfDocumentBuilder b = dracoBuilder(m, draco, rest, o);
  return b.json(rest);
}

Scene load(const std::string& bytes, const std::string& label = "test.gltf") {
  return loadGltfFromMemory(reinterpret_cast<const unsigned char*>(bytes.data()), bytes.size(), "",
                            label);
}

std::string errorOf(const std::string& bytes) {
  return test::errorOf<SceneError>([&] { load(bytes); });
}

// The scene's triangles as comparable rows: per vertex its position, normal and colour;
// each triangle turned (its winding kept) to start at its smallest vertex, the rows sorted.
using TriangleRow = std::array<float, 30>;
std::vector<TriangleRow> triangleSet(const Scene& s) {
  std::vector<TriangleRow> rows;
  for (size_t t = 0; t < s.triangleCount(); ++t) {
    std::array<std::array<float, 10>, 3> corners;
    for (size_t k = 0; k < 3; ++k) {
      const size_t v = 3 * t + k;
      corners[k] = {s.positions[v].x, s.positions[v].y, s.positions[v].z, s.normals[v].x,
                    s.normals[v].y,   s.normals[v].z,   s.colors[v].r,    s.colors[v].g,
                    s.colors[v].b,    s.colors[v].a};
    }
    std::rotate(corners.begin(), std::min_element(corners.begin(), corners.end()), corners.end());
    TriangleRow row;
    for (size_t k = 0; k < 3; ++k) std::copy(corners[k].begin(), corners[k].end(), &row[10 * k]);
    rows.push_back(row);
  }
  std::sort(rows.begin(), rows.end());
  return rows;
}

TEST(GltfDraco, EdgebreakerMeshEqualsItsUncompressedTwinAsATriangleSet) {
  const TestMesh m;
  const Scene plain = load(plainDocument(m));
  const Scene draco = load(dracoDocument(m, encodeDraco(m, draco::MESH_EDGEBREAKER_ENCODING)));
  ASSERT_EQ(draco.triangleCount(), 12u);
  EXPECT_EQ(triangleSet(draco), triangleSet(plain));  // exact: no quantisation
  EXPECT_EQ(draco.dropped_zero_area + draco.dropped_degenerate, 0u);
}

// Sequential connectivity keeps the triangle and vertex order: the loaded scene (and so its
// render) is the uncompressed one's, array for array, including an attribute stored
// uncompressed beside the Draco data, read as usual (the specification).
TEST(GltfDraco, SequentialMeshLoadsAsItsUncompressedTwinInOrder) {
  const TestMesh m;
  const Scene plain = load(plainDocument(m));
  const Scene draco =
      load(dracoDocument(m, encodeDraco(m, draco::MESH_SEQUENTIAL_ENCODING), {8, kNormalId, true}));
  EXPECT_EQ(draco.positions, plain.positions);
  EXPECT_EQ(draco.normals, plain.normals);
  EXPECT_EQ(draco.colors, plain.colors);
  EXPECT_EQ(draco.texcoords[0], plain.texcoords[0]);
  EXPECT_EQ(draco.material_of, plain.material_of);
}

TEST(GltfDraco, DracoInsideAGlbLoads) {
  const TestMesh m;
  std::string rest;
  const GltfDocumentBuilder b =
      dracoBuilder(m, encodeDraco(m, draco::MESH_SEQUENTIAL_ENCODING), rest);
  const Scene draco = load(b.glb(rest), "test.glb");
  EXPECT_EQ(draco.positions, load(plainDocument(m)).positions);
}

// Half a 14-bit quantisation step over the box's largest extent (Draco rounds each
// coordinate to the nearest step), with 1% for the float arithmetic of dequantising.
constexpr float kBoxExtent = 3.1f;  // z from 2.5 to 5.5, the largest of the three
constexpr float kQuantised14BitError = kBoxExtent / float((1 << 14) - 1) * 0.5f * 1.01f;

TEST(GltfDraco, QuantisedPositionsStayWithinHalfAStep) {
  const TestMesh m;
  const Scene plain = load(plainDocument(m));
  const Scene draco = load(dracoDocument(m, encodeDraco(m, draco::MESH_SEQUENTIAL_ENCODING, 14)));
  ASSERT_EQ(draco.positions.size(), plain.positions.size());
  float largest = 0.0f;
  for (size_t i = 0; i < plain.positions.size(); ++i)
    for (int c = 0; c < 3; ++c) {
      const float error = std::abs(draco.positions[i][c] - plain.positions[i][c]);
      largest = std::max(largest, error);
      EXPECT_LE(error, kQuantised14BitError) << "vertex " << i << " axis " << c;
    }
  EXPECT_GT(largest, 0.0f);  // quantised indeed
}

TEST(GltfDraco, MalformedDracoDataNamesThePrimitive) {
  const TestMesh m;
  const std::string draco = encodeDraco(m, draco::MESH_EDGEBREAKER_ENCODING);
  for (const std::string& broken :
       {draco.substr(0, draco.size() / 2), std::string("not Draco data at all")}) {
    const std::string message = errorOf(dracoDocument(m, broken));
    EXPECT_NE(message.find("test.gltf: mesh 0 primitive 0: malformed Draco data"),
              std::string::npos)
        << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
}

TEST(GltfDraco, AnAttributeIdTheDataLacksIsNamed) {
  const TestMesh m;
  const std::string message =
      errorOf(dracoDocument(m, encodeDraco(m, draco::MESH_EDGEBREAKER_ENCODING), {8, 42}));
  EXPECT_NE(message.find("mesh 0 primitive 0: the Draco data has no attribute id 42 (NORMAL)"),
            std::string::npos)
      << message;
}

TEST(GltfDraco, AnAccessorCountUnlikeTheDecodedPointsIsAnError) {
  const TestMesh m;
  const std::string message =
      errorOf(dracoDocument(m, encodeDraco(m, draco::MESH_EDGEBREAKER_ENCODING), {9}));
  EXPECT_NE(message.find("mesh 0 primitive 0: POSITION (accessor 0): count 9 differs from the 8 "
                         "points of the Draco data"),
            std::string::npos)
      << message;
}

}  // namespace
}  // namespace gridrt
