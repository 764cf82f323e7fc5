#include "gltf_meshopt.h"

#include <meshoptimizer.h>

#include <cstdint>
#include <optional>
#include <utility>
#include <vector>

#include "gltf_accessors.h"

namespace gridrt::gltf {
namespace {

constexpr const char* kExtension = "EXT_meshopt_compression";

struct CompressedView {
  uint64_t buffer = 0, byte_offset = 0, byte_length = 0, byte_stride = 0, count = 0;
  std::string mode, filter = "NONE";
};

std::string stringMember(const tinygltf::Value& object, const char* key) {
  if (!object.Has(key) || !object.Get(key).IsString()) return {};
  return object.Get(key).Get<std::string>();
}

CompressedView readExtension(const tinygltf::Value& ext, const std::string& where,
                             const std::string& label) {
  if (!ext.IsObject()) fail(label, where + ": not an object");
  CompressedView out;
  auto required = [&](const char* key, uint64_t& value) {
    const std::optional<uint64_t> v = wholeNumber(ext, key);
    if (!v) fail(label, where + ": " + key + " is missing or not a whole number");
    value = *v;
  };
  required("buffer", out.buffer);
  required("byteLength", out.byte_length);
  required("byteStride", out.byte_stride);
  required("count", out.count);
  if (ext.Has("byteOffset")) required("byteOffset", out.byte_offset);
  out.mode = stringMember(ext, "mode");
  if (ext.Has("filter")) out.filter = stringMember(ext, "filter");
  return out;
}

// The specification's rules on the extension object, in its order.
void checkRules(const CompressedView& c, const tinygltf::BufferView& view, const std::string& where,
                const std::string& label) {
  auto broken = [&](const std::string& what) { fail(label, where + ": " + what); };
  if (view.byteStride != 0 && view.byteStride != c.byte_stride)
    broken("byteStride " + std::to_string(c.byte_stride) + " differs from the bufferView's " +
           std::to_string(view.byteStride));
  uint64_t decoded = 0;
  if (__builtin_mul_overflow(c.byte_stride, c.count, &decoded) || decoded != view.byteLength)
    broken("count " + std::to_string(c.count) + " * byteStride " + std::to_string(c.byte_stride) +
           " differs from the bufferView's byteLength " + std::to_string(view.byteLength));
  if (c.mode == "ATTRIBUTES") {
    if (c.byte_stride == 0 || c.byte_stride % 4 != 0 || c.byte_stride > 256)
      broken("ATTRIBUTES need a byteStride divisible by 4, at most 256, not " +
             std::to_string(c.byte_stride));
  } else if (c.mode == "TRIANGLES" || c.mode == "INDICES") {
    if (c.mode == "TRIANGLES" && c.count % 3 != 0)
      broken("TRIANGLES need a count divisible by 3, not " + std::to_string(c.count));
    if (c.byte_stride != 2 && c.byte_stride != 4)
      broken(c.mode + " need a byteStride of 2 or 4, not " + std::to_string(c.byte_stride));
    if (c.filter != "NONE") broken(c.mode + " take no filter, not " + c.filter);
  } else {
    broken("mode '" + c.mode + "' is not ATTRIBUTES, TRIANGLES or INDICES");
  }
  if (c.filter == "OCTAHEDRAL" && c.byte_stride != 4 && c.byte_stride != 8)
    broken("OCTAHEDRAL needs a byteStride of 4 or 8, not " + std::to_string(c.byte_stride));
  else if (c.filter == "QUATERNION" && c.byte_stride != 8)
    broken("QUATERNION needs a byteStride of 8, not " + std::to_string(c.byte_stride));
  else if (c.filter != "NONE" && c.filter != "OCTAHEDRAL" && c.filter != "QUATERNION" &&
           c.filter != "EXPONENTIAL")
    broken("filter '" + c.filter + "' is not NONE, OCTAHEDRAL, QUATERNION or EXPONENTIAL");
  // EXPONENTIAL's stride divisible by 4 follows from the ATTRIBUTES rule.
  if (decoded / kMaxMeshoptExpansion > c.byte_length)
    broken(std::to_string(c.byte_length) + " compressed bytes cannot decode to " +
           std::to_string(decoded));
}

// Decodes `compressed` into count * byteStride bytes, filters applied.
std::vector<unsigned char> decode(const CompressedView& c, const unsigned char* compressed,
                                  const std::string& where, const std::string& label) {
  std::vector<unsigned char> out(c.count * c.byte_stride);
  if (out.empty()) return out;
  const size_t count = c.count, stride = c.byte_stride, length = c.byte_length;
  int rc = 0;
  if (c.mode == "ATTRIBUTES")
    rc = meshopt_decodeVertexBuffer(out.data(), count, stride, compressed, length);
  else if (c.mode == "TRIANGLES")
    rc = meshopt_decodeIndexBuffer(out.data(), count, stride, compressed, length);
  else
    rc = meshopt_decodeIndexSequence(out.data(), count, stride, compressed, length);
  if (rc != 0)
    fail(label, where + ": malformed " + c.mode + " data (meshopt decoder error " +
                    std::to_string(rc) + ")");
  if (c.filter == "OCTAHEDRAL")
    meshopt_decodeFilterOct(out.data(), count, stride);
  else if (c.filter == "QUATERNION")
    meshopt_decodeFilterQuat(out.data(), count, stride);
  else if (c.filter == "EXPONENTIAL")
    meshopt_decodeFilterExp(out.data(), count, stride);
  return out;
}

}  // namespace

void decodeMeshoptViews(tinygltf::Model& model, const std::string& label) {
  for (size_t v = 0; v < model.bufferViews.size(); ++v) {
    auto ext = model.bufferViews[v].extensions.find(kExtension);
    if (ext == model.bufferViews[v].extensions.end()) continue;
    const std::string where = "bufferView " + std::to_string(v) + " " + kExtension;
    const CompressedView c = readExtension(ext->second, where, label);
    checkRules(c, model.bufferViews[v], where, label);
    if (c.buffer >= model.buffers.size())
      fail(label, where + ": buffer " + std::to_string(c.buffer) + " does not exist");
    const std::vector<unsigned char>& source = model.buffers[c.buffer].data;
    if (c.byte_offset > source.size() || c.byte_length > source.size() - c.byte_offset)
      fail(label, where + ": bytes " + std::to_string(c.byte_offset) + " + " +
                      std::to_string(c.byte_length) + " exceed buffer " + std::to_string(c.buffer) +
                      " of " + std::to_string(source.size()) + " bytes");
    std::vector<unsigned char> decoded = decode(c, source.data() + c.byte_offset, where, label);
    tinygltf::BufferView& view = model.bufferViews[v];
    view.buffer = addBuffer(model, std::move(decoded));
    view.byteOffset = 0;
  }
}

}  // namespace gridrt::gltf
