// Writes a Scene as glTF 2.0, the inverse of the loader: what loadGltfFile reads back is
// the same triangles in the same global order, the same materials, lights and camera.
#pragma once
#include <string>

#include "scene.h"

namespace gridrt {

// ".glb" (any case) writes binary glTF; anything else a .gltf JSON file with the buffer
// embedded as base64. Layout: one node + mesh per run of consecutive triangles sharing a
// material (one per material when the scene is grouped by material), each one primitive
// with float32 POSITION (+ NORMAL when the scene has normals) and uint32 indices 0..n-1;
// the camera as a node with its world matrix; lights as KHR_lights_punctual; materials use
// KHR_materials_transmission / _ior / _volume / _emissive_strength where not default.
// Writes a temporary file next to `path` and renames it, so a failed write never leaves a
// partial file. Throws RenderError (one line, naming the path) when it cannot write.
void writeGltf(const Scene& scene, const std::string& path);

}  // namespace gridrt
