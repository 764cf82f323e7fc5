// The built-in scene the renderer shows when no file is given: a Cornell-like box, open
// towards the camera, holding a mirror sphere, a glass sphere and a diffuse block, lit by
// one point light under the ceiling, so that shadows, reflection and refraction all show.
// Also the few shape builders it is made of, which tools/make_scenes reuses.
#pragma once
#include <glm/glm.hpp>

#include "scene.h"

namespace gridrt {

// Dimensions of the default box (metres).
struct DefaultBox {
  static constexpr float kHalfWidth = 1.0f;  // x in [-1, 1]
  static constexpr float kHeight = 2.0f;     // y in [0, 2], floor at y = 0
  static constexpr float kDepth = 2.0f;      // z in [-2, 0]; the side z = 0 is open
};

// Deterministic: the same triangles in the same order on every call. Triangles come
// grouped by material (one run per material); smooth normals on the spheres, flat ones
// elsewhere; every material is double-sided.
Scene makeDefaultScene();

// Shape builders. Each appends whole triangles (positions, normals, material_of) to a
// scene whose normals are kept per vertex; front faces wind counter-clockwise.
namespace shapes {

int addMaterial(Scene& scene, const Material& material);  // returns its index

// Rectangle centre +- u +- v; its front face (and normal) is cross(u, v).
void addRect(Scene& scene, glm::vec3 centre, glm::vec3 u, glm::vec3 v, int material);

// Box with the given half extents, turned by yaw_radians about +Y; normals outward.
void addBox(Scene& scene, glm::vec3 centre, glm::vec3 half_extents, float yaw_radians,
            int material);

// UV sphere: `rings` latitude bands, `segments` longitude slices, smooth outward normals,
// 2 * segments * (rings - 1) triangles.
void addSphere(Scene& scene, glm::vec3 centre, float radius, int segments, int rings, int material);

// Camera-to-world matrix of a camera at eye looking at target (+Y up as far as possible).
glm::mat4 lookAtWorld(glm::vec3 eye, glm::vec3 target, glm::vec3 up = {0.0f, 1.0f, 0.0f});

}  // namespace shapes
}  // namespace gridrt
