// TEXCOORD_0/1 and COLOR_0 per triangle vertex (gltf_vertex_attributes.h).
#include "gltf_vertex_attributes.h"

#include <cmath>

#include "gltf_accessors.h"

namespace gridrt::gltf {
namespace {

bool isNormalizedUnsigned(const AccessorData& a) {
  return a.normalized && (a.component_type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
                          a.component_type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT);
}

bool isSmallInteger(const AccessorData& a) {
  return a.component_type == TINYGLTF_COMPONENT_TYPE_BYTE ||
         a.component_type == TINYGLTF_COMPONENT_TYPE_SHORT ||
         a.component_type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
         a.component_type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT;
}

[[noreturn]] void wrongType(const AccessorData& a, const std::string& attribute,
                            const std::string& allowed, const std::string& label) {
  fail(label, "accessor " + std::to_string(a.index) + ": " + attribute + " must be " + allowed +
                  ", not " + componentName(a.component_type) + " " + typeName(a.type) +
                  (a.normalized ? " normalized" : ""));
}

AccessorData readCounted(const tinygltf::Model& model, int index, const std::string& attribute,
                         size_t vertex_count, const std::string& where, const std::string& label) {
  AccessorData a = readAccessor(model, index, label);
  if (a.count != vertex_count)
    fail(label, where + ": " + attribute + " has " + std::to_string(a.count) + " elements for " +
                    std::to_string(vertex_count) + " vertices");
  return a;
}

int attributeIndex(const tinygltf::Primitive& prim, const std::string& name) {
  auto it = prim.attributes.find(name);
  return it == prim.attributes.end() ? -1 : it->second;
}

template <typename T>
void appendOne(std::vector<T>& out, const std::optional<std::vector<T>>& values,
               const uint32_t vertices[3], size_t triangles_before, const T& fallback) {
  if (!values && out.empty()) return;  // not started, and nothing to start it
  out.resize(3 * triangles_before, fallback);
  for (int k = 0; k < 3; ++k) out.push_back(values ? (*values)[vertices[k]] : fallback);
}

const glm::vec4 kWhite(1.0f);

}  // namespace

VertexAttributes readVertexAttributes(const tinygltf::Model& model, const tinygltf::Primitive& prim,
                                      size_t vertex_count, bool quantized, const std::string& where,
                                      const std::string& label) {
  VertexAttributes out;
  for (int set = 0; set < 2; ++set) {
    const std::string name = "TEXCOORD_" + std::to_string(set);
    const int index = attributeIndex(prim, name);
    if (index < 0) continue;
    const AccessorData a = readCounted(model, index, name, vertex_count, where, label);
    const bool ok = a.component_type == TINYGLTF_COMPONENT_TYPE_FLOAT || isNormalizedUnsigned(a) ||
                    (quantized && isSmallInteger(a));
    if (!ok || a.type != TINYGLTF_TYPE_VEC2)
      wrongType(a, name,
                std::string("VEC2 of FLOAT or normalized UNSIGNED_BYTE/SHORT") +
                    (quantized ? " (or BYTE/SHORT)" : ""),
                label);
    std::vector<glm::vec2>& uv = out.texcoords[set].emplace(vertex_count);
    for (size_t v = 0; v < vertex_count; ++v) uv[v] = glm::vec2(a.at(v, 0), a.at(v, 1));
  }
  if (const int index = attributeIndex(prim, "COLOR_0"); index >= 0) {
    const AccessorData a = readCounted(model, index, "COLOR_0", vertex_count, where, label);
    const bool ok = a.component_type == TINYGLTF_COMPONENT_TYPE_FLOAT || isNormalizedUnsigned(a);
    if (!ok || (a.type != TINYGLTF_TYPE_VEC3 && a.type != TINYGLTF_TYPE_VEC4))
      wrongType(a, "COLOR_0", "VEC3 or VEC4 of FLOAT or normalized UNSIGNED_BYTE/SHORT", label);
    std::vector<glm::vec4>& colors = out.colors.emplace(vertex_count);
    for (size_t v = 0; v < vertex_count; ++v)
      colors[v] = glm::vec4(a.at(v, 0), a.at(v, 1), a.at(v, 2),
                            a.type == TINYGLTF_TYPE_VEC4 ? a.at(v, 3) : 1.0);
  }
  if (const int index = attributeIndex(prim, "TANGENT"); index >= 0) {
    const AccessorData a = readCounted(model, index, "TANGENT", vertex_count, where, label);
    const bool ok = a.component_type == TINYGLTF_COMPONENT_TYPE_FLOAT ||
                    (quantized && a.normalized &&
                     (a.component_type == TINYGLTF_COMPONENT_TYPE_BYTE ||
                      a.component_type == TINYGLTF_COMPONENT_TYPE_SHORT));
    if (!ok || a.type != TINYGLTF_TYPE_VEC4)
      wrongType(a, "TANGENT",
                std::string("VEC4 of FLOAT") + (quantized ? " (or normalized BYTE/SHORT)" : ""),
                label);
    std::vector<glm::dvec4>& tangents = out.tangents.emplace(vertex_count);
    for (size_t v = 0; v < vertex_count; ++v) tangents[v] = a.vec4(v);
  }
  return out;
}

glm::vec4 worldTangent(const VertexAttributes& attributes, uint32_t vertex,
                       const glm::dmat4& matrix) {
  if (!attributes.tangents) return glm::vec4(0.0f);
  const glm::dvec4& t = (*attributes.tangents)[vertex];
  const glm::dvec3 moved = glm::dmat3(matrix) * glm::dvec3(t);
  const double length = glm::length(moved);
  if (!(length > 0.0) || !std::isfinite(length)) return glm::vec4(0.0f);
  const bool mirrors = glm::determinant(glm::dmat3(matrix)) < 0.0;
  const float sign = (t.w < 0.0) != mirrors ? -1.0f : 1.0f;
  return glm::vec4(glm::vec3(moved / length), sign);
}

void appendTriangleAttributes(const VertexAttributes& attributes, const uint32_t vertices[3],
                              const glm::vec4 tangents[3], size_t triangles_before, Scene& scene) {
  for (int set = 0; set < 2; ++set)
    appendOne(scene.texcoords[set], attributes.texcoords[set], vertices, triangles_before,
              glm::vec2(0.0f));
  appendOne(scene.colors, attributes.colors, vertices, triangles_before, kWhite);
  if (!attributes.tangents && scene.tangents.empty()) return;
  scene.tangents.resize(3 * triangles_before, glm::vec4(0.0f));
  for (int k = 0; k < 3; ++k) scene.tangents.push_back(tangents[k]);
}

bool appendsTriangleAttributes(const VertexAttributes& attributes, const Scene& scene) {
  // The cases where appendOne and the tangents step above return at once, all together.
  for (int set = 0; set < 2; ++set)
    if (attributes.texcoords[set] || !scene.texcoords[set].empty()) return true;
  return attributes.colors || !scene.colors.empty() || attributes.tangents ||
         !scene.tangents.empty();
}

void finishVertexAttributes(Scene& scene) {
  const size_t vertices = scene.positions.size();
  for (auto& uv : scene.texcoords)
    if (!uv.empty()) uv.resize(vertices, glm::vec2(0.0f));
  if (!scene.colors.empty()) scene.colors.resize(vertices, kWhite);
  if (!scene.tangents.empty()) scene.tangents.resize(vertices, glm::vec4(0.0f));
}

}  // namespace gridrt::gltf
