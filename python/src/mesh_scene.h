// A scene made from a mesh's arrays (gridrt.Scene(vertices, faces)): N x 3 vertex
// positions, M x 3 vertex indices, every triangle with the default material. Triangles no
// ray can hit (zero area) are left out as every loader leaves them out, and each kept
// triangle remembers its face's row, so that hits name the caller's rows.
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

#include "scene.h"

namespace gridrt {

struct MeshScene {
  Scene scene;
  std::vector<int32_t> face_of;  // per triangle of scene: its row in the faces array
};

// vertices: vertex_count x 3 floats, row-major; faces: face_count x 3 indices, row-major.
// Throws UsageError naming the row for a NaN or infinite coordinate, an index outside
// 0..vertex_count-1, or a mesh without any triangle of non-zero area.
MeshScene meshScene(const float* vertices, size_t vertex_count, const int64_t* faces,
                    size_t face_count);

}  // namespace gridrt
