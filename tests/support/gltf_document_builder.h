// Small glTF documents written by tests: one buffer embedded as a base64 data URI (or a
// .glb's BIN chunk), with a buffer view and an accessor per array added, and nodes whose
// numbers are written with 17 significant digits (read back as the same doubles).
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <glm/glm.hpp>
#include <optional>
#include <string>
#include <vector>

#include "test_support.h"

namespace gridrt::test {

constexpr int kGltfUnsignedByte = 5121, kGltfUnsignedShort = 5123, kGltfFloat = 5126;

// A number as JSON that reads back as the same double.
inline std::string exactNumber(double v) {
  char text[40];
  std::snprintf(text, sizeof text, "%.17g", v);
  return text;
}

inline std::string exactNumbers(const std::vector<double>& values) {
  std::string out = "[";
  for (size_t i = 0; i < values.size(); ++i) out += (i ? "," : "") + exactNumber(values[i]);
  return out + "]";
}

// A node: `members` holds its other JSON members ("\"mesh\":0", "\"children\":[2]", ...).
struct TestNode {
  std::string members;
  std::optional<glm::dvec3> translation;
  std::optional<glm::dvec4> rotation;
  std::optional<glm::dvec3> scale;
  std::optional<std::vector<double>> weights;

  std::string json() const {
    std::string out = "{" + members;
    auto add = [&](const char* key, const std::vector<double>& v) {
      out += std::string(out.size() > 1 ? "," : "") + "\"" + key + "\":" + exactNumbers(v);
    };
    if (translation) add("translation", {translation->x, translation->y, translation->z});
    if (rotation) add("rotation", {rotation->x, rotation->y, rotation->z, rotation->w});
    if (scale) add("scale", {scale->x, scale->y, scale->z});
    if (weights) add("weights", *weights);
    return out + "}";
  }
};

inline std::string nodesJson(const std::vector<TestNode>& nodes) {
  std::string out = "\"nodes\":[";
  for (size_t i = 0; i < nodes.size(); ++i) out += (i ? "," : "") + nodes[i].json();
  return out + "]";
}

// A GLB container: header, JSON chunk (space-padded), BIN chunk (zero-padded) if any.
inline std::string makeGlb(std::string json, std::string bin) {
  auto u32 = [](uint32_t v) { return std::string(reinterpret_cast<const char*>(&v), 4); };
  json.resize((json.size() + 3) / 4 * 4, ' ');
  bin.resize((bin.size() + 3) / 4 * 4, '\0');
  const size_t total = 12 + 8 + json.size() + (bin.empty() ? 0 : 8 + bin.size());
  std::string glb =
      "glTF" + u32(2) + u32(uint32_t(total)) + u32(uint32_t(json.size())) + "JSON" + json;
  if (!bin.empty()) glb += u32(uint32_t(bin.size())) + std::string("BIN\0", 4) + bin;
  return glb;
}

class GltfDocumentBuilder {
 public:
  // An accessor over a new buffer view of `bytes`; `extra`: further accessor members.
  int addAccessor(const std::string& bytes, int component_type, size_t count,
                  const std::string& type, const std::string& extra = "") {
    return addRawAccessor("{\"bufferView\":" + std::to_string(addView(bytes)) +
                          ",\"componentType\":" + std::to_string(component_type) + ",\"count\":" +
                          std::to_string(count) + ",\"type\":\"" + type + "\"" + extra + "}");
  }
  // A buffer view over `bytes`, 4-byte aligned in buffer 0; returns its index.
  int addView(const std::string& bytes) {
    const size_t view_offset = addBytes(bytes);
    return addRawView("{\"buffer\":0,\"byteOffset\":" + std::to_string(view_offset) +
                      ",\"byteLength\":" + std::to_string(bytes.size()) + "}");
  }
  // Appends `bytes` to buffer 0 (4-byte aligned); returns their offset.
  size_t addBytes(const std::string& bytes) {
    const size_t offset = bin_.size();
    bin_ += bytes;
    bin_.resize((bin_.size() + 3) / 4 * 4, '\0');
    return offset;
  }
  // A buffer view, accessor or buffer after buffer 0, given as JSON; returns its index.
  int addRawView(const std::string& json) {
    views_.push_back(json);
    return int(views_.size() - 1);
  }
  int addRawAccessor(const std::string& json) {
    accessors_.push_back(json);
    return int(accessors_.size() - 1);
  }
  int addRawBuffer(const std::string& json) {
    more_buffers_.push_back(json);
    return int(more_buffers_.size());
  }
  // FLOAT accessors of `type` (SCALAR 1, VEC3 3, VEC4 4, MAT4 16 numbers an element).
  int floats(const std::vector<float>& values, const std::string& type) {
    const size_t per = type == "SCALAR" ? 1
                       : type == "VEC2" ? 2
                       : type == "VEC3" ? 3
                       : type == "VEC4" ? 4
                                        : 16;
    std::string extra;
    const bool finite =
        std::all_of(values.begin(), values.end(), [](float v) { return std::isfinite(v); });
    if (type == "SCALAR" && !values.empty() && finite) {  // animation inputs have min and max
      const auto [lo, hi] = std::minmax_element(values.begin(), values.end());
      extra = ",\"min\":[" + exactNumber(*lo) + "],\"max\":[" + exactNumber(*hi) + "]";
    }
    return addAccessor(bytesOf(values), kGltfFloat, values.size() / per, type, extra);
  }
  int bytes(const std::vector<uint8_t>& values, const std::string& type) {
    return addAccessor(bytesOf(values), kGltfUnsignedByte, values.size() / 4, type);
  }

  // The document: `rest` holds the other top-level members without braces.
  std::string json(const std::string& rest) const {
    return document(",\"uri\":\"data:application/octet-stream;base64," + base64(bin_) + "\"", rest);
  }
  // The document as a .glb, buffer 0 its BIN chunk.
  std::string glb(const std::string& rest) const { return makeGlb(document("", rest), bin_); }

 private:
  std::string document(const std::string& buffer_uri, const std::string& rest) const {
    std::string doc = "{\"asset\":{\"version\":\"2.0\"}";
    if (!bin_.empty()) {
      std::vector<std::string> buffers = {"{\"byteLength\":" + std::to_string(bin_.size()) +
                                          buffer_uri + "}"};
      buffers.insert(buffers.end(), more_buffers_.begin(), more_buffers_.end());
      doc += ",\"buffers\":[" + join(buffers) + "],\"bufferViews\":[" + join(views_) +
             "],\"accessors\":[" + join(accessors_) + "]";
    }
    return doc + (rest.empty() ? "" : "," + rest) + "}";
  }
  static std::string join(const std::vector<std::string>& items) {
    std::string out;
    for (const auto& s : items) out += (out.empty() ? "" : ",") + s;
    return out;
  }
  std::string bin_;
  std::vector<std::string> views_, accessors_, more_buffers_;
};

}  // namespace gridrt::test
