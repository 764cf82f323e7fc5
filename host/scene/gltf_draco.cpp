#include "gltf_draco.h"

#include <draco/compression/decode.h>

#include <cstdint>
#include <limits>
#include <memory>
#include <utility>
#include <vector>

#include "gltf_accessors.h"

namespace gridrt::gltf {
namespace {

constexpr const char* kExtension = "KHR_draco_mesh_compression";

struct Context {
  tinygltf::Model& model;
  const std::string& where;  // the primitive, for messages
  const std::string& label;
  [[noreturn]] void fail(const std::string& what) const { gltf::fail(label, where + ": " + what); }
};

// A new accessor like the file's `original` (its count, type, component type, bounds)
// over a new buffer holding `bytes`.
int addDecodedAccessor(tinygltf::Model& model, const tinygltf::Accessor& original,
                       std::vector<unsigned char> bytes) {
  tinygltf::BufferView view;
  view.byteLength = bytes.size();
  view.buffer = addBuffer(model, std::move(bytes));
  model.bufferViews.push_back(std::move(view));
  tinygltf::Accessor accessor = original;
  accessor.bufferView = int(model.bufferViews.size() - 1);
  accessor.byteOffset = 0;
  accessor.sparse = {};
  model.accessors.push_back(std::move(accessor));
  return int(model.accessors.size() - 1);
}

const tinygltf::Accessor& fileAccessor(const Context& c, int index, const std::string& role) {
  if (index < 0 || size_t(index) >= c.model.accessors.size())
    c.fail(role + " accessor " + std::to_string(index) + " does not exist");
  return c.model.accessors[size_t(index)];
}

// Every point's value of `attribute` as `components` values of type T (Draco converts,
// and refuses values T cannot hold).
template <typename T>
bool convertValues(const draco::Mesh& mesh, const draco::PointAttribute& attribute, int components,
                   std::vector<unsigned char>& out) {
  out.resize(size_t(mesh.num_points()) * size_t(components) * sizeof(T));
  T* values = reinterpret_cast<T*>(out.data());
  for (uint32_t p = 0; p < mesh.num_points(); ++p)
    if (!attribute.ConvertValue<T>(attribute.mapped_index(draco::PointIndex(p)), int8_t(components),
                                   values + size_t(p) * size_t(components)))
      return false;
  return true;
}

// The decoded values of `attribute` under accessor `index`'s layout; returns the new accessor.
int decodedAttribute(const Context& c, const std::string& semantic, int index,
                     const draco::Mesh& mesh, const draco::PointAttribute& attribute) {
  const tinygltf::Accessor& accessor = fileAccessor(c, index, semantic);
  const int components = tinygltf::GetNumComponentsInType(uint32_t(accessor.type));
  const std::string name = semantic + " (accessor " + std::to_string(index) + ")";
  if (accessor.count != mesh.num_points())
    c.fail(name + ": count " + std::to_string(accessor.count) + " differs from the " +
           std::to_string(mesh.num_points()) + " points of the Draco data");
  if (components != attribute.num_components())
    c.fail(name + ": " + typeName(accessor.type) + " but the Draco attribute has " +
           std::to_string(int(attribute.num_components())) + " components");
  std::vector<unsigned char> bytes;
  bool ok = false;
  switch (accessor.componentType) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
      ok = convertValues<int8_t>(mesh, attribute, components, bytes);
      break;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      ok = convertValues<uint8_t>(mesh, attribute, components, bytes);
      break;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
      ok = convertValues<int16_t>(mesh, attribute, components, bytes);
      break;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
      ok = convertValues<uint16_t>(mesh, attribute, components, bytes);
      break;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
      ok = convertValues<uint32_t>(mesh, attribute, components, bytes);
      break;
    case TINYGLTF_COMPONENT_TYPE_FLOAT:
      ok = convertValues<float>(mesh, attribute, components, bytes);
      break;
    default:
      c.fail(name + ": unsupported component type " + std::to_string(accessor.componentType));
  }
  if (!ok) c.fail(name + ": the Draco values do not fit " + componentName(accessor.componentType));
  return addDecodedAccessor(c.model, accessor, std::move(bytes));
}

template <typename T>
std::vector<unsigned char> faceIndices(const draco::Mesh& mesh) {
  std::vector<unsigned char> out(size_t(mesh.num_faces()) * 3 * sizeof(T));
  T* values = reinterpret_cast<T*>(out.data());
  for (uint32_t f = 0; f < mesh.num_faces(); ++f)
    for (int k = 0; k < 3; ++k)
      values[size_t(f) * 3 + size_t(k)] = T(mesh.face(draco::FaceIndex(f))[k].value());
  return out;
}

// The decoded triangles under the indices accessor `index` (none: a new UNSIGNED_INT one).
int decodedIndices(const Context& c, int index, const draco::Mesh& mesh) {
  tinygltf::Accessor accessor;
  accessor.componentType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
  accessor.type = TINYGLTF_TYPE_SCALAR;
  accessor.count = size_t(mesh.num_faces()) * 3;
  if (index >= 0) accessor = fileAccessor(c, index, "indices");
  const std::string name = "indices (accessor " + std::to_string(index) + ")";
  if (accessor.count != size_t(mesh.num_faces()) * 3)
    c.fail(name + ": count " + std::to_string(accessor.count) + " differs from the " +
           std::to_string(mesh.num_faces()) + " triangles of the Draco data");
  const uint64_t largest = mesh.num_points() == 0 ? 0 : mesh.num_points() - 1;
  switch (accessor.componentType) {
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      if (largest <= std::numeric_limits<uint8_t>::max())
        return addDecodedAccessor(c.model, accessor, faceIndices<uint8_t>(mesh));
      break;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
      if (largest <= std::numeric_limits<uint16_t>::max())
        return addDecodedAccessor(c.model, accessor, faceIndices<uint16_t>(mesh));
      break;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
      return addDecodedAccessor(c.model, accessor, faceIndices<uint32_t>(mesh));
    default:
      c.fail(name + ": indices must be UNSIGNED_BYTE/SHORT/INT, not " +
             componentName(accessor.componentType));
  }
  c.fail(name + ": " + componentName(accessor.componentType) + " cannot index the " +
         std::to_string(mesh.num_points()) + " points of the Draco data");
}

std::unique_ptr<draco::Mesh> decodeMesh(const Context& c, const tinygltf::Value& extension) {
  const std::optional<uint64_t> view = wholeNumber(extension, "bufferView");
  if (!view || *view > uint64_t(std::numeric_limits<int>::max()))
    c.fail(std::string(kExtension) + " has no valid bufferView");
  const ViewBytes bytes = bufferViewBytes(c.model, int(*view), c.where + " " + kExtension, c.label);
  draco::DecoderBuffer buffer;
  buffer.Init(reinterpret_cast<const char*>(bytes.data), bytes.size);
  auto type = draco::Decoder::GetEncodedGeometryType(&buffer);
  if (!type.ok()) c.fail("malformed Draco data: " + type.status().error_msg_string());
  if (type.value() != draco::TRIANGULAR_MESH)
    c.fail("the Draco data is not a triangle mesh (a point cloud?)");
  draco::Decoder decoder;
  auto decoded = decoder.DecodeMeshFromBuffer(&buffer);
  if (!decoded.ok()) c.fail("malformed Draco data: " + decoded.status().error_msg_string());
  return std::move(decoded).value();
}

void decodePrimitive(const Context& c, tinygltf::Primitive& primitive,
                     const tinygltf::Value& extension) {
  if (!extension.IsObject()) c.fail(std::string(kExtension) + " is not an object");
  const std::unique_ptr<draco::Mesh> mesh = decodeMesh(c, extension);
  const tinygltf::Value& attributes = extension.Get("attributes");
  if (!attributes.IsObject()) c.fail(std::string(kExtension) + " has no attributes object");
  for (const std::string& semantic : attributes.Keys()) {
    const std::optional<uint64_t> id = wholeNumber(attributes, semantic.c_str());
    if (!id || *id > std::numeric_limits<uint32_t>::max())
      c.fail("Draco attribute id of " + semantic + " is not a whole number");
    auto target = primitive.attributes.find(semantic);
    if (target == primitive.attributes.end())
      c.fail("Draco attribute " + semantic + " is not an attribute of the primitive");
    const draco::PointAttribute* attribute = mesh->GetAttributeByUniqueId(uint32_t(*id));
    if (!attribute)
      c.fail("the Draco data has no attribute id " + std::to_string(*id) + " (" + semantic + ")");
    target->second = decodedAttribute(c, semantic, target->second, *mesh, *attribute);
  }
  primitive.indices = decodedIndices(c, primitive.indices, *mesh);
}

}  // namespace

void decodeDracoPrimitives(tinygltf::Model& model, const std::string& label) {
  for (size_t m = 0; m < model.meshes.size(); ++m) {
    for (size_t p = 0; p < model.meshes[m].primitives.size(); ++p) {
      tinygltf::Primitive& primitive = model.meshes[m].primitives[p];
      auto extension = primitive.extensions.find(kExtension);
      if (extension == primitive.extensions.end()) continue;
      if (primitive.mode != TINYGLTF_MODE_TRIANGLES && primitive.mode != -1) continue;
      const std::string where =
          named("mesh", m, model.meshes[m].name) + " primitive " + std::to_string(p);
      decodePrimitive(Context{model, where, label}, primitive, extension->second);
    }
  }
}

}  // namespace gridrt::gltf
