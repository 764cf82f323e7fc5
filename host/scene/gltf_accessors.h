// glTF accessors decoded into doubles, every element checked against its buffer view and
// buffer (tinygltf checks none of it):
// - every component type; normalized integers mapped as the glTF specification says
//   (unsigned c / (2^b - 1), signed max(c / (2^(b-1) - 1), -1)), which is what
//   KHR_mesh_quantization's attributes need;
// - sparse accessors: the base (the buffer view, or zeros without one) with the listed
//   elements replaced, their indices strictly increasing and in range.
// A double holds every glTF component exactly (floats, and integers up to 32 bits), so a
// FLOAT accessor read here and cast back to float is the file's value bit for bit.
#pragma once
#include <tiny_gltf.h>

#include <cstddef>
#include <cstdint>
#include <glm/glm.hpp>
#include <optional>
#include <string>
#include <vector>

#include "uninitialized_vector.h"

namespace gridrt::gltf {

// tinygltf reports several problems separated by newlines, and file content (names, the
// JSON parser's "last read" excerpt) may hold control characters; messages are one line.
std::string oneLine(const std::string& text);

// Throws SceneError("label: what") on one line.
[[noreturn]] void fail(const std::string& label, const std::string& what);

// "kind N 'name'", or "kind N" when the name is empty: how messages name an element.
std::string named(const std::string& kind, size_t index, const std::string& name);

const char* componentName(int component_type);  // "UNSIGNED_SHORT", ...
const char* typeName(int type);                 // "VEC3", ...

struct AccessorData {
  int index = -1;  // the accessor's index in the file, for messages
  size_t count = 0;
  int components = 0;  // per element: 1 (SCALAR) .. 16 (MAT4)
  int component_type = 0;
  int type = 0;
  bool normalized = false;
  // count * components, element-major (sized without zeroing: every value is read in).
  UninitializedVector<double> values;

  double at(size_t element, int component) const {
    return values[element * size_t(components) + size_t(component)];
  }
  glm::dvec3 vec3(size_t i) const { return {at(i, 0), at(i, 1), at(i, 2)}; }
  glm::dvec4 vec4(size_t i) const { return {at(i, 0), at(i, 1), at(i, 2), at(i, 3)}; }
  // Column-major, as glTF stores matrices.
  glm::dmat4 mat4(size_t i) const;
};

// Reads accessor `index` of `model`; `label` names the file in messages.
AccessorData readAccessor(const tinygltf::Model& model, int index, const std::string& label);

// The bytes of buffer view `view_index`, checked to lie inside its buffer; `where` names the
// reader in messages.
struct ViewBytes {
  const unsigned char* data = nullptr;
  size_t size = 0;
};
ViewBytes bufferViewBytes(const tinygltf::Model& model, int view_index, const std::string& where,
                          const std::string& label);

// Member `key` of an extension object when it is a whole number in [0, 2^53]; nullopt when
// it is absent, not a number, negative or fractional.
std::optional<uint64_t> wholeNumber(const tinygltf::Value& object, const char* key);

// Decoded data (Draco, meshopt) as a new buffer of the model; returns its index.
int addBuffer(tinygltf::Model& model, std::vector<unsigned char> bytes);

}  // namespace gridrt::gltf
