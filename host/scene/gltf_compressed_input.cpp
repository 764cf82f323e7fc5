#include "gltf_compressed_input.h"

#include <cstdint>
#include <cstring>
#include <limits>
#include <string>

#include "prefault.h"

namespace gridrt::gltf {
namespace {

// What a placeholder buffer becomes for tinygltf: one byte (tinygltf refuses an empty
// data URI), emptied again after parsing.
constexpr const char* kPlaceholderUri = "data:application/octet-stream;base64,AA==";

const nlohmann::json* member(const nlohmann::json& object, const char* key) {
  if (!object.is_object()) return nullptr;
  auto it = object.find(key);
  return it == object.end() ? nullptr : &*it;
}

const nlohmann::json* extensionOf(const nlohmann::json& object, const char* name) {
  const nlohmann::json* extensions = member(object, "extensions");
  return extensions ? member(*extensions, name) : nullptr;
}

bool usesMeshopt(const nlohmann::json& doc) {
  const nlohmann::json* views = member(doc, "bufferViews");
  if (!views || !views->is_array()) return false;
  for (const auto& view : *views)
    if (extensionOf(view, "EXT_meshopt_compression")) return true;
  return false;
}

// Draco primitives lose their `indices`, placeholder buffers become one-byte data URIs;
// returns whether anything changed.
bool liftCompressedMembers(nlohmann::json& doc, bool binary, CompressedInput& input) {
  if (nlohmann::json* meshes = doc.contains("meshes") ? &doc["meshes"] : nullptr;
      meshes && meshes->is_array())
    for (size_t m = 0; m < meshes->size(); ++m) {
      nlohmann::json& mesh = (*meshes)[m];
      if (!mesh.is_object() || !mesh.contains("primitives") || !mesh["primitives"].is_array())
        continue;
      nlohmann::json& primitives = mesh["primitives"];
      for (size_t p = 0; p < primitives.size(); ++p) {
        nlohmann::json& primitive = primitives[p];
        const nlohmann::json* indices = member(primitive, "indices");
        // Another value is left to tinygltf to refuse.
        if (!extensionOf(primitive, "KHR_draco_mesh_compression") || !indices ||
            !indices->is_number_integer() || *indices < 0 ||
            *indices > std::numeric_limits<int>::max())
          continue;
        input.draco_indices.push_back({m, p, indices->get<int>()});
        primitive.erase("indices");
      }
    }
  if (usesMeshopt(doc) && doc.contains("buffers") && doc["buffers"].is_array()) {
    nlohmann::json& buffers = doc["buffers"];
    for (size_t b = 0; b < buffers.size(); ++b) {
      nlohmann::json& buffer = buffers[b];
      if (!buffer.is_object() || buffer.contains("uri") || (binary && b == 0)) continue;
      buffer["uri"] = kPlaceholderUri;
      buffer["byteLength"] = 1;
      input.placeholder_buffers.push_back(b);
    }
  }
  return !input.draco_indices.empty() || !input.placeholder_buffers.empty();
}

// Where a .glb's JSON chunk ends (header, chunk length and type, text): its other chunks
// follow. 0 when the file is too short to hold it.
size_t glbJsonChunkEnd(const unsigned char* data, size_t size) {
  uint32_t json_length = 0;
  if (size < 20) return 0;
  std::memcpy(&json_length, data + 12, 4);  // GLB is little-endian, like our hosts
  return json_length > size - 20 ? 0 : 20 + size_t(json_length);
}

// Buffer 0's bytes in a .glb's binary chunk, when they may be set aside (the header
// comment of prepareCompressedInput); null otherwise.
const unsigned char* binaryToSetAside(const nlohmann::json& doc, const unsigned char* data,
                                      size_t size, size_t& bytes) {
  uint32_t chunk_length = 0, chunk_type = 0;
  const size_t chunk = glbJsonChunkEnd(data, size);  // the binary chunk's header
  if (chunk == 0 || chunk + 8 > size) return nullptr;
  std::memcpy(&chunk_length, data + chunk, 4);
  std::memcpy(&chunk_type, data + chunk + 4, 4);
  // tinygltf's checks of the chunk (LoadBinaryFromMemory): left to it to refuse.
  if (chunk_type != 0x004E4942u || chunk_length % 4 != 0 || chunk_length < kSetAsideBinaryBytes ||
      chunk_length > size - chunk - 8)
    return nullptr;
  const nlohmann::json* buffers = member(doc, "buffers");
  if (!buffers || !buffers->is_array() || buffers->empty()) return nullptr;
  const nlohmann::json& buffer = (*buffers)[0];
  const nlohmann::json* length = member(buffer, "byteLength");
  if (!buffer.is_object() || buffer.contains("uri") || !length || !length->is_number_unsigned() ||
      length->get<uint64_t>() > chunk_length)
    return nullptr;
  if (const nlohmann::json* images = member(doc, "images"); images && images->is_array())
    for (const auto& image : *images)
      if (member(image, "bufferView")) return nullptr;
  bytes = size_t(length->get<uint64_t>());
  return data + chunk + 8;
}

void appendUint32(std::vector<unsigned char>& out, uint32_t value) {
  unsigned char bytes[4];
  std::memcpy(bytes, &value, 4);  // GLB is little-endian, like our hosts
  out.insert(out.end(), bytes, bytes + 4);
}

}  // namespace

CompressedInput prepareCompressedInput(const nlohmann::json& doc, const unsigned char* data,
                                       size_t size, bool binary) {
  CompressedInput input;
  if (!doc.is_object()) return input;
  nlohmann::json changed = doc;
  const bool lifted = liftCompressedMembers(changed, binary, input);
  if (binary) input.glb_binary = binaryToSetAside(doc, data, size, input.glb_binary_bytes);
  if (input.glb_binary) {
    changed["buffers"][0]["uri"] = kPlaceholderUri;
    changed["buffers"][0]["byteLength"] = 1;
  }
  if (!lifted && !input.glb_binary) return input;
  std::string json = changed.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
  if (!binary) {
    input.bytes.assign(json.begin(), json.end());
    return input;
  }
  // A .glb: header (magic, version, length), the JSON chunk (length, type, text padded
  // with spaces to 4 bytes), then the file's other chunks as they are (none when the binary
  // chunk is set aside: a .glb without one is valid).
  const size_t rest = glbJsonChunkEnd(data, size);
  if (rest == 0) return {};
  json.resize((json.size() + 3) / 4 * 4, ' ');
  input.bytes.assign(data, data + 12);
  appendUint32(input.bytes, uint32_t(json.size()));
  input.bytes.insert(input.bytes.end(), data + 16, data + 20);  // the chunk type
  input.bytes.insert(input.bytes.end(), json.begin(), json.end());
  if (!input.glb_binary) input.bytes.insert(input.bytes.end(), data + rest, data + size);
  const uint32_t total = uint32_t(input.bytes.size());
  std::memcpy(input.bytes.data() + 8, &total, 4);
  return input;
}

void restoreCompressedInput(const CompressedInput& input, tinygltf::Model& model) {
  if (input.glb_binary && !model.buffers.empty()) {
    std::vector<unsigned char>& data = model.buffers[0].data;
    data.clear();
    reserveFaultedIn(data, input.glb_binary_bytes);  // on every core (prefault.h)
    data.assign(input.glb_binary, input.glb_binary + input.glb_binary_bytes);
    model.buffers[0].uri.clear();
  }
  for (const auto& lifted : input.draco_indices)
    if (lifted.mesh < model.meshes.size() &&
        lifted.primitive < model.meshes[lifted.mesh].primitives.size())
      model.meshes[lifted.mesh].primitives[lifted.primitive].indices = lifted.accessor;
  for (size_t b : input.placeholder_buffers)
    if (b < model.buffers.size()) {
      model.buffers[b].data.clear();
      model.buffers[b].uri.clear();
    }
}

}  // namespace gridrt::gltf
