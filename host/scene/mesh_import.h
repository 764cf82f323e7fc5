// Mesh files other than glTF (OBJ with its MTL, PLY, STL and whatever else Debian's
// libassimp reads) -> the Scene the glTF loader makes:
// - Triangles: polygons triangulated by assimp; points and lines skipped and counted in
//   Scene::skipped_primitives. Nodes depth-first from the root, a node's meshes in order
//   before its children; world = parent * local, in double precision, the winding kept
//   counter-clockwise under mirroring transforms, as the glTF loader keeps it.
// - Normals where the file has them (world space, inverse transpose), as for glTF;
//   vertex colours (a PLY's, say) as COLOR_0, as stored.
// - Materials: Kd is the base colour; a highlight where Ks is not black and Ns > 0,
//   with the roughness whose Phong exponent is Ns (exponent 2/α² − 2, roughness √α; no
//   highlight: roughness 1); Ke the emission. Metallic 0: no mirror. assimp's default
//   material (a mesh without one) is gridrt's default Material.
// - No camera and no lights: the renderer frames the scene and adds its default lights;
//   a file's cameras, lights, textures and animations are ignored with a warning.
// - The loader's checks: vertex indices in range (else a SceneError), triangles with
//   NaN/Inf coordinates or zero area dropped and counted (scene_triangles.h).
// Unreadable files are a SceneError: "PATH: " and assimp's message, on one line.
#pragma once
#include <string>

#include "scene.h"

namespace gridrt {

// True where assimp reads files with the extension of `path`, except glTF's (.gltf, .glb:
// the glTF loader reads those).
bool isImportedMeshFile(const std::string& path);

Scene importMeshFile(const std::string& path);

}  // namespace gridrt
