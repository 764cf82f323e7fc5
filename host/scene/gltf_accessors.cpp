#include "gltf_accessors.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <optional>

#include "errors.h"
#include "parallel_loops.h"
#include "prefault.h"

namespace gridrt::gltf {

std::string oneLine(const std::string& text) {
  std::string out;
  bool pending_break = false;
  for (char c : text) {
    if (c == '\n' || c == '\r') {
      pending_break = true;
      continue;
    }
    if (pending_break && !out.empty()) out += "; ";
    pending_break = false;
    out += (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) ? '?' : c;
  }
  while (!out.empty() && (out.back() == ' ' || out.back() == ';')) out.pop_back();
  return out;
}

void fail(const std::string& label, const std::string& what) {
  throw SceneError(oneLine(label + ": " + what));
}

std::string named(const std::string& kind, size_t index, const std::string& name) {
  std::string s = kind + " " + std::to_string(index);
  if (!name.empty()) s += " '" + name + "'";
  return s;
}

const char* componentName(int component_type) {
  switch (component_type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
      return "BYTE";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return "UNSIGNED_BYTE";
    case TINYGLTF_COMPONENT_TYPE_SHORT:
      return "SHORT";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
      return "UNSIGNED_SHORT";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
      return "UNSIGNED_INT";
    case TINYGLTF_COMPONENT_TYPE_FLOAT:
      return "FLOAT";
    default:
      return "an invalid component type";
  }
}

const char* typeName(int type) {
  switch (type) {
    case TINYGLTF_TYPE_SCALAR:
      return "SCALAR";
    case TINYGLTF_TYPE_VEC2:
      return "VEC2";
    case TINYGLTF_TYPE_VEC3:
      return "VEC3";
    case TINYGLTF_TYPE_VEC4:
      return "VEC4";
    case TINYGLTF_TYPE_MAT2:
      return "MAT2";
    case TINYGLTF_TYPE_MAT3:
      return "MAT3";
    case TINYGLTF_TYPE_MAT4:
      return "MAT4";
    default:
      return "?";
  }
}

glm::dmat4 AccessorData::mat4(size_t i) const {
  glm::dmat4 m;
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) m[c][r] = at(i, c * 4 + r);
  return m;
}

namespace {

size_t componentSize(int component_type) {
  switch (component_type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return 1;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
      return 2;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
    case TINYGLTF_COMPONENT_TYPE_FLOAT:
      return 4;
    default:
      return 0;  // INT and DOUBLE are not glTF 2.0 accessor types
  }
}

// offset + stride * (count - 1) + element, or nullopt on overflow.
std::optional<size_t> accessorEnd(size_t offset, size_t stride, size_t count, size_t element) {
  if (count == 0) return offset;
  size_t span, end;
  if (__builtin_mul_overflow(stride, count - 1, &span)) return std::nullopt;
  if (__builtin_add_overflow(offset, span, &end)) return std::nullopt;
  if (__builtin_add_overflow(end, element, &end)) return std::nullopt;
  return end;
}

// Bytes [offset, offset + stride * (count - 1) + element) of buffer view `view_index`,
// checked to lie inside the view and the view inside its buffer. `where` names the reader.
const unsigned char* viewBytes(const tinygltf::Model& model, int view_index, size_t offset,
                               size_t stride, size_t count, size_t element,
                               const std::string& where, const std::string& label) {
  if (view_index < 0 || size_t(view_index) >= model.bufferViews.size())
    fail(label, where + ": bufferView " + std::to_string(view_index) + " does not exist");
  const tinygltf::BufferView& view = model.bufferViews[size_t(view_index)];
  const std::string view_name = "bufferView " + std::to_string(view_index);
  if (view.buffer < 0 || size_t(view.buffer) >= model.buffers.size())
    fail(label,
         where + ": " + view_name + ": buffer " + std::to_string(view.buffer) + " does not exist");
  const std::vector<unsigned char>& buffer = model.buffers[size_t(view.buffer)].data;
  auto view_end = accessorEnd(view.byteOffset, 0, 1, view.byteLength);
  if (!view_end || *view_end > buffer.size())
    fail(label, where + ": " + view_name + ": bytes " + std::to_string(view.byteOffset) + " + " +
                    std::to_string(view.byteLength) + " exceed buffer " +
                    std::to_string(view.buffer) + " of " + std::to_string(buffer.size()) +
                    " bytes");
  auto end = accessorEnd(offset, stride, count, element);
  if (!end || *end > view.byteLength)
    fail(label, where + ": " + std::to_string(count) + " elements at offset " +
                    std::to_string(offset) + " with stride " + std::to_string(stride) + " exceed " +
                    view_name + " of " + std::to_string(view.byteLength) + " bytes");
  return buffer.data() + view.byteOffset + offset;
}

// One component at p, as stored (normalized == false) or normalized.
double component(const unsigned char* p, int component_type, bool normalized) {
  switch (component_type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE: {
      int8_t v;
      std::memcpy(&v, p, 1);
      return normalized ? std::max(v / 127.0, -1.0) : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return normalized ? p[0] / 255.0 : p[0];
    case TINYGLTF_COMPONENT_TYPE_SHORT: {
      int16_t v;
      std::memcpy(&v, p, 2);
      return normalized ? std::max(v / 32767.0, -1.0) : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
      uint16_t v;
      std::memcpy(&v, p, 2);
      return normalized ? v / 65535.0 : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: {
      uint32_t v;
      std::memcpy(&v, p, 4);
      return normalized ? v / 4294967295.0 : v;
    }
    default: {
      float v;
      std::memcpy(&v, p, 4);
      return v;
    }
  }
}

// Elements of `components` components each, read from `data` `stride` bytes apart: one
// loop per component type, so the type's switch is not taken per component (it was a
// fifth of a 93 MB scene's load).
template <typename T>
void readElementsOf(const unsigned char* data, size_t stride, size_t count, int components,
                    int component_type, bool normalized, double* out) {
  if (normalized) {
    for (size_t i = 0; i < count; ++i)
      for (int c = 0; c < components; ++c)
        out[i * size_t(components) + size_t(c)] =
            component(data + i * stride + size_t(c) * sizeof(T), component_type, true);
    return;
  }
  for (size_t i = 0; i < count; ++i)
    for (int c = 0; c < components; ++c) {
      T v;
      std::memcpy(&v, data + i * stride + size_t(c) * sizeof(T), sizeof(T));
      out[i * size_t(components) + size_t(c)] = double(v);
    }
}

// Elements below which one core reads an accessor: a parallel loop costs about what a few
// thousand conversions do.
constexpr size_t kParallelReadElements = size_t(1) << 16;

void readElements(const unsigned char* data, size_t stride, size_t count, int components,
                  int component_type, bool normalized, double* out) {
  // In consecutive ranges on every core when there are many (a mesh of millions of
  // vertices); each element is converted alone, so the values are the same either way.
  auto read = [&](auto type) {
    const int slices = count >= kParallelReadElements ? parallelSliceCount() : 1;
    parallelSlices(slices, [&](int me, int n) {
      const auto [first, last] = sliceRange(count, me, n);
      readElementsOf<decltype(type)>(data + first * stride, stride, last - first, components,
                                     component_type, normalized, out + first * size_t(components));
    });
  };
  switch (component_type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
      return read(int8_t{});
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return read(uint8_t{});
    case TINYGLTF_COMPONENT_TYPE_SHORT:
      return read(int16_t{});
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
      return read(uint16_t{});
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
      return read(uint32_t{});
    default:  // FLOAT (componentSize refused the rest), never normalized
      normalized = false;
      return read(float{});
  }
}

void applySparse(const tinygltf::Model& model, const tinygltf::Accessor& acc,
                 const std::string& where, const std::string& label, AccessorData& out) {
  const auto& sparse = acc.sparse;
  if (sparse.count < 1 || size_t(sparse.count) > acc.count)
    fail(label, where + ": sparse count " + std::to_string(sparse.count) + " is not in 1.." +
                    std::to_string(acc.count));
  const size_t n = size_t(sparse.count);
  const int index_type = sparse.indices.componentType;
  if (index_type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
      index_type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
      index_type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
    fail(label, where + ": sparse indices must be UNSIGNED_BYTE/SHORT/INT, not " +
                    componentName(index_type));
  if (sparse.indices.byteOffset < 0 || sparse.values.byteOffset < 0)
    fail(label, where + ": negative sparse byteOffset");
  const size_t index_size = componentSize(index_type);
  const unsigned char* indices =
      viewBytes(model, sparse.indices.bufferView, size_t(sparse.indices.byteOffset), index_size, n,
                index_size, where + " sparse indices", label);
  const size_t element = componentSize(out.component_type) * size_t(out.components);
  const unsigned char* values =
      viewBytes(model, sparse.values.bufferView, size_t(sparse.values.byteOffset), element, n,
                element, where + " sparse values", label);
  std::vector<double> replaced(n * size_t(out.components));
  readElements(values, element, n, out.components, out.component_type, out.normalized,
               replaced.data());
  double previous = -1;
  for (size_t k = 0; k < n; ++k) {
    const double target = component(indices + k * index_size, index_type, false);
    if (target <= previous || target >= double(acc.count))
      fail(label, where + ": sparse index " + std::to_string(uint64_t(target)) +
                      (target <= previous ? " does not increase" : " out of range for ") +
                      (target <= previous ? "" : std::to_string(acc.count) + " elements"));
    previous = target;
    std::copy_n(replaced.begin() + std::ptrdiff_t(k) * out.components, out.components,
                out.values.begin() + std::ptrdiff_t(target) * out.components);
  }
}

}  // namespace

AccessorData readAccessor(const tinygltf::Model& model, int index, const std::string& label) {
  if (index < 0 || size_t(index) >= model.accessors.size())
    fail(label, "accessor " + std::to_string(index) + " does not exist (" +
                    std::to_string(model.accessors.size()) + " accessors)");
  const tinygltf::Accessor& acc = model.accessors[size_t(index)];
  const std::string where = "accessor " + std::to_string(index);
  const size_t size = componentSize(acc.componentType);
  const int components = tinygltf::GetNumComponentsInType(static_cast<uint32_t>(acc.type));
  if (size == 0 || components <= 0)
    fail(label, where + ": unsupported component type " + std::to_string(acc.componentType));

  AccessorData out;
  out.index = index;
  out.count = acc.count;
  out.components = components;
  out.component_type = acc.componentType;
  out.type = acc.type;
  out.normalized = acc.normalized;
  size_t total;
  if (__builtin_mul_overflow(acc.count, size_t(components), &total) || total > (size_t{1} << 32))
    fail(label, where + ": " + std::to_string(acc.count) + " elements is too many");

  if (acc.bufferView < 0) {
    // Only a sparse accessor may leave its buffer view out: its base is then all zeros.
    if (!acc.sparse.isSparse)
      fail(label, where + ": bufferView " + std::to_string(acc.bufferView) + " does not exist");
    out.values.assign(total, 0.0);
  } else {
    const size_t element = size * size_t(components);
    const tinygltf::BufferView* view = size_t(acc.bufferView) < model.bufferViews.size()
                                           ? &model.bufferViews[acc.bufferView]
                                           : nullptr;
    const size_t stride = view && view->byteStride != 0 ? view->byteStride : element;
    if (view && (stride < element || stride % size != 0))
      fail(label, "bufferView " + std::to_string(acc.bufferView) + ": byteStride " +
                      std::to_string(stride) + " does not fit " + std::to_string(element) +
                      "-byte elements of " + where);
    const unsigned char* data =
        viewBytes(model, acc.bufferView, acc.byteOffset, stride, acc.count, element, where, label);
    reserveFaultedIn(out.values, total);  // on every core (prefault.h): tens of MB at times
    out.values.resize(total);
    readElements(data, stride, acc.count, components, acc.componentType, acc.normalized,
                 out.values.data());
  }
  if (acc.sparse.isSparse) applySparse(model, acc, where, label, out);
  return out;
}

ViewBytes bufferViewBytes(const tinygltf::Model& model, int view_index, const std::string& where,
                          const std::string& label) {
  if (view_index < 0 || size_t(view_index) >= model.bufferViews.size())
    fail(label, where + ": bufferView " + std::to_string(view_index) + " does not exist");
  const size_t length = model.bufferViews[size_t(view_index)].byteLength;
  return {viewBytes(model, view_index, 0, 0, 1, length, where, label), length};
}

std::optional<uint64_t> wholeNumber(const tinygltf::Value& object, const char* key) {
  if (!object.IsObject() || !object.Has(key)) return std::nullopt;
  const tinygltf::Value& v = object.Get(key);
  if (!v.IsNumber()) return std::nullopt;
  const double d = v.GetNumberAsDouble();
  if (!(d >= 0.0 && d <= 9007199254740992.0) || d != std::floor(d)) return std::nullopt;
  return uint64_t(d);
}

int addBuffer(tinygltf::Model& model, std::vector<unsigned char> bytes) {
  tinygltf::Buffer buffer;
  buffer.data = std::move(bytes);
  model.buffers.push_back(std::move(buffer));
  return int(model.buffers.size() - 1);
}

}  // namespace gridrt::gltf
