// EXT_meshopt_compression: buffer views compressed here with meshoptimizer's own encoder
// (its filters included), behind a placeholder buffer, loaded, and compared with the same
// data stored uncompressed.
#include <gtest/gtest.h>
#include <meshoptimizer.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "errors.h"
#include "gltf_accessors.h"
#include "gltf_document_builder.h"
#include "gltf_loader.h"

namespace gridrt {
namespace {

using test::bytesOf;
using test::GltfDocumentBuilder;

constexpr int kUShort = 5123, kUInt = 5125, kShort = 5122, kFloat = 5126;

// Octahedral normals in 16 bits: the two octahedral coordinates are 1/32767 apart, and the
// normal they unfold to is rounded again to 16-bit components; measured up to 2.24 steps.
constexpr float kOctahedral16BitError = 3.0f / 32767.0f;
// Quaternions in 16 bits: three components rounded to 16 bits, the fourth recomputed from
// them; measured up to 1.27 steps.
constexpr float kQuaternion16BitError = 2.0f / 32767.0f;

// The slanted box of the Draco tests, its coordinates multiples of 1/64 so that the
// EXPONENTIAL filter (24-bit mantissas sharing the vertex's exponent) keeps them exactly.
const std::vector<float> kPositions = {
    0.09375f,  -1.703125f, 3.25f,     2.59375f,  -1.203125f, 3.0f,      2.90625f,  1.3125f,
    2.5f,      0.34375f,   0.796875f, 2.75f,     -0.1875f,   -1.5f,     5.5f,      2.296875f,
    -1.09375f, 5.203125f,  2.640625f, 1.453125f, 4.796875f,  0.046875f, 1.046875f, 5.0f};
const std::vector<uint32_t> kIndices = {0, 2, 1, 0, 3, 2, 4, 5, 6, 4, 6, 7, 0, 1, 5, 0, 5, 4,
                                        1, 2, 6, 1, 6, 5, 2, 3, 7, 2, 7, 6, 3, 0, 4, 3, 4, 7};
constexpr size_t kVertices = 8;

std::vector<float> unitNormals() {
  std::vector<float> out;
  for (size_t v = 0; v < kVertices; ++v) {
    const glm::vec3 p(kPositions[3 * v], kPositions[3 * v + 1], kPositions[3 * v + 2]);
    const glm::vec3 n = glm::normalize(p - glm::vec3(1.3f, -0.2f, 3.9f));
    out.insert(out.end(), {n.x, n.y, n.z});
  }
  return out;
}

std::string encodedVertices(const void* data, size_t count, size_t stride) {
  std::string out(meshopt_encodeVertexBufferBound(count, stride), '\0');
  out.resize(meshopt_encodeVertexBuffer(reinterpret_cast<unsigned char*>(out.data()), out.size(),
                                        data, count, stride));
  return out;
}

// Builds a document whose compressed views decode into a placeholder buffer (buffer 1).
class MeshoptDocument {
 public:
  // A view of `count` elements of `stride` bytes, compressed as `encoded`; returns its index.
  int view(const std::string& encoded, size_t count, size_t stride, const std::string& mode,
           const std::string& filter = "NONE", bool vertex_stride = true) {
    const size_t offset = b_.addBytes(encoded);
    const size_t length = count * stride;
    const std::string json =
        "{\"buffer\":1,\"byteOffset\":" + std::to_string(fallback_bytes_) +
        ",\"byteLength\":" + std::to_string(length) +
        (vertex_stride ? ",\"byteStride\":" + std::to_string(stride) : "") +
        ",\"extensions\":{\"EXT_meshopt_compression\":{\"buffer\":0,\"byteOffset\":" +
        std::to_string(offset) + ",\"byteLength\":" + std::to_string(encoded.size()) +
        ",\"byteStride\":" + std::to_string(stride) + ",\"count\":" + std::to_string(count) +
        ",\"mode\":\"" + mode + "\",\"filter\":\"" + filter + "\"}}}";
    fallback_bytes_ += (length + 3) / 4 * 4;
    return b_.addRawView(json);
  }
  int accessor(int view, int component, size_t count, const std::string& type,
               const std::string& extra = "") {
    return b_.addRawAccessor("{\"bufferView\":" + std::to_string(view) + ",\"componentType\":" +
                             std::to_string(component) + ",\"count\":" + std::to_string(count) +
                             ",\"type\":\"" + type + "\"" + extra + "}");
  }
  GltfDocumentBuilder& builder() { return b_; }
  // `rest` after the extension declarations and the placeholder buffer.
  std::string rest(const std::string& members) {
    b_.addRawBuffer("{\"byteLength\":" + std::to_string(fallback_bytes_) +
                    ",\"extensions\":{\"EXT_meshopt_compression\":{\"fallback\":true}}}");
    return "\"extensionsUsed\":[\"EXT_meshopt_compression\",\"KHR_mesh_quantization\"],"
           "\"extensionsRequired\":[\"EXT_meshopt_compression\",\"KHR_mesh_quantization\"]," +
           members;
  }

 private:
  GltfDocumentBuilder b_;
  size_t fallback_bytes_ = 0;
};

const std::string kScene = "\"scene\":0,\"scenes\":[{\"nodes\":[0]}],\"nodes\":[{\"mesh\":0}]";

std::string primitive(int position, int indices, int normal = -1) {
  return "{\"attributes\":{\"POSITION\":" + std::to_string(position) +
         (normal >= 0 ? ",\"NORMAL\":" + std::to_string(normal) : "") +
         "},\"indices\":" + std::to_string(indices) + "}";
}

// Two primitives: the box with 16-bit octahedral normals and TRIANGLES-coded indices, and
// the box again with EXPONENTIAL-filtered positions and INDICES-coded 32-bit indices.
MeshoptDocument compressedBoxes(std::string& rest) {
  MeshoptDocument d;
  const int pos = d.accessor(
      d.view(encodedVertices(kPositions.data(), kVertices, 12), kVertices, 12, "ATTRIBUTES"),
      kFloat, kVertices, "VEC3");
  const std::vector<float> normals = unitNormals();
  std::vector<float> normals4;
  for (size_t v = 0; v < kVertices; ++v)
    normals4.insert(normals4.end(), {normals[3 * v], normals[3 * v + 1], normals[3 * v + 2], 0});
  std::vector<int16_t> octahedral(4 * kVertices);
  meshopt_encodeFilterOct(octahedral.data(), kVertices, 8, 16, normals4.data());
  const int nrm = d.accessor(d.view(encodedVertices(octahedral.data(), kVertices, 8), kVertices, 8,
                                    "ATTRIBUTES", "OCTAHEDRAL"),
                             kShort, kVertices, "VEC3", ",\"normalized\":true");
  std::string triangles(meshopt_encodeIndexBufferBound(kIndices.size(), kVertices), '\0');
  triangles.resize(meshopt_encodeIndexBuffer(reinterpret_cast<unsigned char*>(triangles.data()),
                                             triangles.size(), kIndices.data(), kIndices.size()));
  const int idx = d.accessor(d.view(triangles, kIndices.size(), 2, "TRIANGLES", "NONE", false),
                             kUShort, kIndices.size(), "SCALAR");

  std::vector<uint32_t> exponential(3 * kVertices);
  meshopt_encodeFilterExp(exponential.data(), kVertices, 12, 24, kPositions.data());
  const int pos2 = d.accessor(d.view(encodedVertices(exponential.data(), kVertices, 12), kVertices,
                                     12, "ATTRIBUTES", "EXPONENTIAL"),
                              kFloat, kVertices, "VEC3");
  std::string sequence(meshopt_encodeIndexSequenceBound(kIndices.size(), kVertices), '\0');
  sequence.resize(meshopt_encodeIndexSequence(reinterpret_cast<unsigned char*>(sequence.data()),
                                              sequence.size(), kIndices.data(), kIndices.size()));
  const int idx2 = d.accessor(d.view(sequence, kIndices.size(), 4, "INDICES", "NONE", false), kUInt,
                              kIndices.size(), "SCALAR");
  rest = d.rest(kScene + ",\"meshes\":[{\"primitives\":[" + primitive(pos, idx, nrm) + "," +
                primitive(pos2, idx2) + "]}]");
  return d;
}

std::string plainBoxes() {
  GltfDocumentBuilder b;
  const int pos = b.floats(kPositions, "VEC3"), nrm = b.floats(unitNormals(), "VEC3");
  const std::vector<uint16_t> short_indices(kIndices.begin(), kIndices.end());
  const int idx = b.addAccessor(bytesOf(short_indices), kUShort, kIndices.size(), "SCALAR");
  const int idx2 = b.addAccessor(bytesOf(kIndices), kUInt, kIndices.size(), "SCALAR");
  return b.json(kScene + ",\"meshes\":[{\"primitives\":[" + primitive(pos, idx, nrm) + "," +
                primitive(pos, idx2) + "]}]");
}

Scene load(const std::string& bytes, const std::string& label = "test.gltf") {
  return loadGltfFromMemory(reinterpret_cast<const unsigned char*>(bytes.data()), bytes.size(), "",
                            label);
}

// Per triangle its vertices (position and normal), turned to start at the smallest
// position: meshoptimizer's TRIANGLES encoder may rotate a triangle (its winding kept).
using Corner = std::array<float, 6>;
std::vector<std::array<Corner, 3>> turnedTriangles(const Scene& s) {
  std::vector<std::array<Corner, 3>> out;
  for (size_t t = 0; t < s.triangleCount(); ++t) {
    std::array<Corner, 3> tri;
    for (size_t k = 0; k < 3; ++k) {
      const glm::vec3 &p = s.positions[3 * t + k], &n = s.normals[3 * t + k];
      tri[k] = {p.x, p.y, p.z, n.x, n.y, n.z};
    }
    std::rotate(tri.begin(), std::min_element(tri.begin(), tri.end()), tri.end());
    out.push_back(tri);
  }
  return out;
}

void expectTwins(const Scene& meshopt, const Scene& plain) {
  ASSERT_EQ(meshopt.triangleCount(), 24u);
  ASSERT_EQ(meshopt.normals.size(), plain.normals.size());
  const auto got = turnedTriangles(meshopt), want = turnedTriangles(plain);
  float largest = 0.0f;
  for (size_t t = 0; t < got.size(); ++t)
    for (size_t k = 0; k < 3; ++k) {
      for (size_t c = 0; c < 3; ++c)  // positions exact: meshopt is lossless
        EXPECT_EQ(got[t][k][c], want[t][k][c]) << "triangle " << t << " vertex " << k;
      for (size_t c = 3; c < 6; ++c) {  // the second primitive has face normals: exact too
        const float error = std::abs(got[t][k][c] - want[t][k][c]);
        largest = std::max(largest, error);
        EXPECT_LE(error, t < 12 ? kOctahedral16BitError : 0.0f) << "triangle " << t;
      }
    }
  EXPECT_GT(largest, 0.0f);  // the octahedral filter rounds indeed
}

TEST(GltfMeshopt, CompressedViewsLoadAsTheirUncompressedTwin) {
  std::string rest;
  MeshoptDocument d = compressedBoxes(rest);
  expectTwins(load(d.builder().json(rest)), load(plainBoxes()));
}

// In a .glb the placeholder is buffer 1 without a uri, longer than the BIN chunk.
TEST(GltfMeshopt, CompressedViewsInAGlbLoad) {
  std::string rest;
  MeshoptDocument d = compressedBoxes(rest);
  expectTwins(load(d.builder().glb(rest), "test.glb"), load(plainBoxes()));
}

// Rotations as an animation stores them, through the QUATERNION filter.
TEST(GltfMeshopt, QuaternionFilterDecodesRotations) {
  const std::vector<glm::vec4> rotations = {glm::normalize(glm::vec4(0.1f, 0.7f, -0.2f, 0.6f)),
                                            glm::normalize(glm::vec4(-0.9f, 0.1f, 0.3f, 0.2f)),
                                            glm::vec4(0.0f, 0.0f, 0.0f, 1.0f)};
  std::vector<int16_t> encoded(4 * rotations.size());
  meshopt_encodeFilterQuat(encoded.data(), rotations.size(), 8, 16, &rotations[0].x);
  MeshoptDocument d;
  const int rot = d.accessor(d.view(encodedVertices(encoded.data(), rotations.size(), 8),
                                    rotations.size(), 8, "ATTRIBUTES", "QUATERNION"),
                             kShort, rotations.size(), "VEC4", ",\"normalized\":true");
  const std::string json = d.builder().json(d.rest(kScene));
  const GltfDocument doc = GltfDocument::fromMemory(
      reinterpret_cast<const unsigned char*>(json.data()), json.size(), "", "test.gltf");
  const gltf::AccessorData values = gltf::readAccessor(doc.model(), rot, "test.gltf");
  for (size_t r = 0; r < rotations.size(); ++r) {
    // q and -q are the same rotation; the filter may return either.
    const double sign = glm::dot(glm::dvec4(values.vec4(r)), glm::dvec4(rotations[r])) < 0 ? -1 : 1;
    for (int c = 0; c < 4; ++c)
      EXPECT_NEAR(sign * values.at(r, c), rotations[r][c], kQuaternion16BitError)
          << "rotation " << r << " component " << c;
  }
}

// A document of one compressed ATTRIBUTES view of the box's positions whose extension
// members `edit` changes.
std::string brokenView(const std::function<void(std::string&)>& edit) {
  MeshoptDocument d;
  const int view =
      d.view(encodedVertices(kPositions.data(), kVertices, 12), kVertices, 12, "ATTRIBUTES");
  const int pos = d.accessor(view, kFloat, kVertices, "VEC3");
  const std::vector<uint16_t> indices(kIndices.begin(), kIndices.end());
  const int idx = d.builder().addAccessor(bytesOf(indices), kUShort, indices.size(), "SCALAR");
  std::string json = d.builder().json(
      d.rest(kScene + ",\"meshes\":[{\"primitives\":[" + primitive(pos, idx) + "]}]"));
  edit(json);
  return json;
}

void replace(std::string& text, const std::string& from, const std::string& to) {
  const size_t at = text.find(from);
  ASSERT_NE(at, std::string::npos) << from;
  text.replace(at, from.size(), to);
}

std::string errorOf(const std::string& json) {
  return test::errorOf<SceneError>([&] { load(json); });
}

TEST(GltfMeshopt, BrokenViewsAreOneLineErrorsNamingTheView) {
  const std::string where = "test.gltf: bufferView 0 EXT_meshopt_compression: ";
  const struct {
    std::function<void(std::string&)> edit;
    std::string message;
  } cases[] = {
      {[](std::string& j) { replace(j, "\"mode\":\"ATTRIBUTES\"", "\"mode\":\"VERTICES\""); },
       "mode 'VERTICES' is not ATTRIBUTES, TRIANGLES or INDICES"},
      {[](std::string& j) { replace(j, "\"filter\":\"NONE\"", "\"filter\":\"QUATERNION\""); },
       "QUATERNION needs a byteStride of 8, not 12"},
      {[](std::string& j) { replace(j, "\"count\":8", "\"count\":7"); },
       "count 7 * byteStride 12 differs from the bufferView's byteLength 96"},
      // The compressed stream's header byte (0xa0, base64 "o") made wrong.
      {[](std::string& j) { replace(j, "base64,o", "base64,A"); },
       "malformed ATTRIBUTES data (meshopt decoder error"},
      {[](std::string& j) { replace(j, "\"buffer\":0,", "\"buffer\":1,"); },
       "exceed buffer 1 of 0 bytes"},  // the placeholder holds no data
  };
  for (const auto& c : cases) {
    const std::string message = errorOf(brokenView(c.edit));
    EXPECT_EQ(message.rfind(where, 0), 0u) << message;
    EXPECT_NE(message.find(c.message), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
}

// A view claiming more decoded bytes than any stream of its length can hold is refused
// before its decoded size is allocated.
TEST(GltfMeshopt, AViewClaimingMoreThanItsDataCanHoldIsRefused) {
  const size_t count = 6000;  // 72000 bytes from about 100: no valid stream expands so much
  const std::string message = errorOf(brokenView([&](std::string& j) {
    replace(j, "\"byteLength\":96,\"byteStride\":12", "\"byteLength\":72000,\"byteStride\":12");
    replace(j, "\"count\":8", "\"count\":" + std::to_string(count));
  }));
  EXPECT_NE(message.find("compressed bytes cannot decode to 72000"), std::string::npos) << message;
}

}  // namespace
}  // namespace gridrt
