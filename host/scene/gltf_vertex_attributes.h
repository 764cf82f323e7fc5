// The vertex attributes beside POSITION and NORMAL that shading reads: TEXCOORD_0,
// TEXCOORD_1 and COLOR_0, read per primitive and stored per triangle vertex in the Scene
// (Scene::texcoords, Scene::colors), like its normals.
//
// - TEXCOORD_n: VEC2, FLOAT or normalized UNSIGNED_BYTE/SHORT (glTF); with
//   KHR_mesh_quantization also BYTE/SHORT, normalized or not, and non-normalized unsigned.
// - COLOR_0: VEC3 (alpha 1) or VEC4, FLOAT or normalized UNSIGNED_BYTE/SHORT.
// - TANGENT: VEC4, FLOAT (with KHR_mesh_quantization also normalized BYTE/SHORT), moved
//   to world space by the vertex's matrix (worldTangent).
// Anything else is a SceneError naming the accessor; a count unlike POSITION's too.
// Morph targets of these attributes are not applied (the still pose moves positions and
// normals only).
#pragma once
#include <tiny_gltf.h>

#include <cstdint>
#include <glm/glm.hpp>
#include <optional>
#include <string>
#include <vector>

#include "scene.h"

namespace gridrt::gltf {

// One primitive's attributes, per vertex of the primitive; nullopt where it has none.
struct VertexAttributes {
  std::optional<std::vector<glm::vec2>> texcoords[2];
  std::optional<std::vector<glm::vec4>> colors;
  std::optional<std::vector<glm::dvec4>> tangents;  // as the file stores them
};

VertexAttributes readVertexAttributes(const tinygltf::Model& model, const tinygltf::Primitive& prim,
                                      size_t vertex_count, bool quantized, const std::string& where,
                                      const std::string& label);

// Appends one triangle's attributes (its vertices in the order they are stored) to the
// scene, which holds `triangles_before` triangles before it. A scene array starts when the
// first primitive with the attribute does, filled with the default for the triangles
// before it ((0, 0) texture coordinates, white); once started, primitives without the
// attribute add the default.
// tangents: the vertices' world tangents (worldTangent).
void appendTriangleAttributes(const VertexAttributes& attributes, const uint32_t vertices[3],
                              const glm::vec4 tangents[3], size_t triangles_before, Scene& scene);
// Whether appendTriangleAttributes adds anything for a primitive with `attributes` to
// `scene`: false when neither has any of them (a loader may then skip the per-triangle call).
bool appendsTriangleAttributes(const VertexAttributes& attributes, const Scene& scene);

// Vertex `vertex`'s tangent moved by `matrix` (its xyz unit, w the sign of the file's w
// times that of the matrix's determinant, so that the bitangent mirrors with the mesh);
// zero when the primitive has no TANGENT or the tangent is zero or not finite.
glm::vec4 worldTangent(const VertexAttributes& attributes, uint32_t vertex,
                       const glm::dmat4& matrix);

// Pads the started arrays with the default to every triangle of the scene.
void finishVertexAttributes(Scene& scene);

}  // namespace gridrt::gltf
