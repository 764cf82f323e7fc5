// What every loader (glTF, assimp's formats) does with a world-space triangle on its way
// into the Scene: triangles no ray can hit are dropped and counted, normals are unit length
// or fall back to the face's, and the scene's warnings sum up what was left out.
#pragma once
#include <glm/glm.hpp>

#include "scene.h"

namespace gridrt {

bool isFinite(const glm::vec3& v);

// Shading needs unit normals; a zero or non-finite vector falls back to `fallback`.
glm::vec3 unitOr(const glm::dvec3& v, const glm::vec3& fallback);

// The unit normal of the winding a, b, c (any unit vector for a zero-area triangle).
glm::vec3 geometricNormal(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c);

// False, counting it, for a triangle with a NaN/Inf vertex (Scene::dropped_degenerate) or
// exactly zero area (Scene::dropped_zero_area; computed in double, where the float
// vertices are exact): no ray can hit it, and Moeller-Trumbore would report garbage hits
// on repeated vertices.
bool keepTriangle(const glm::vec3 (&p)[3], Scene& scene);

// keepTriangle in two steps, for loaders that judge triangles on several cores: the
// verdict alone, then counted in the scene's totals (true for Kept).
enum class TriangleVerdict : unsigned char { Kept, Degenerate, ZeroArea };
TriangleVerdict triangleVerdict(const glm::vec3 (&p)[3]);
bool countVerdict(TriangleVerdict verdict, Scene& scene);

// Appends a kept triangle: its vertices, their normals (zero, meaning none usable, becomes
// the face normal) and its material.
void addTriangle(const glm::vec3 (&p)[3], const glm::vec3 (&n)[3], int material, Scene& scene);
// The three positions and normals addTriangle stores for a kept triangle.
void triangleCorners(const glm::vec3 (&p)[3], const glm::vec3 (&n)[3], glm::vec3* positions,
                     glm::vec3* normals);

// Normals are all-or-nothing: without any triangle that came with normals, there are none.
void finishNormals(bool any_normals, Scene& scene);

// Warnings that count the skipped primitives and the dropped triangles.
void addDropWarnings(Scene& scene);

}  // namespace gridrt
