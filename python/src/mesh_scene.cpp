#include "mesh_scene.h"

#include <cmath>
#include <string>

#include "errors.h"
#include "scene_triangles.h"

namespace gridrt {

MeshScene meshScene(const float* vertices, size_t vertex_count, const int64_t* faces,
                    size_t face_count) {
  for (size_t i = 0; i < vertex_count * 3; ++i)
    if (!std::isfinite(vertices[i]))
      throw UsageError("vertices: row " + std::to_string(i / 3) +
                       " holds a NaN or infinite coordinate");
  MeshScene mesh;
  Scene& scene = mesh.scene;
  scene.materials.push_back(Material{});
  const glm::vec3 no_normals[3]{};  // addTriangle gives each the face's normal
  for (size_t f = 0; f < face_count; ++f) {
    glm::vec3 p[3];
    for (int k = 0; k < 3; ++k) {
      const int64_t v = faces[f * 3 + k];
      if (v < 0 || uint64_t(v) >= vertex_count)
        throw UsageError("faces: row " + std::to_string(f) + " names vertex " + std::to_string(v) +
                         ", outside 0.." + std::to_string(int64_t(vertex_count) - 1));
      p[k] = glm::vec3(vertices[v * 3], vertices[v * 3 + 1], vertices[v * 3 + 2]);
    }
    if (!countVerdict(triangleVerdict(p), scene)) continue;
    addTriangle(p, no_normals, 0, scene);
    mesh.face_of.push_back(int32_t(f));
  }
  finishNormals(false, scene);
  if (mesh.face_of.empty())
    throw UsageError("faces: no triangle of non-zero area among " + std::to_string(face_count) +
                     " rows");
  addDropWarnings(scene);
  return mesh;
}

}  // namespace gridrt
