// glTF 2.0 (.gltf / .glb) -> gridrt::Scene, through tinygltf.
//
// What the loader produces (see scene.h for the fields):
// - Traversal: the default scene (`scene`, else scene 0; with no scenes at all, every node
//   that is nobody's child, in index order). Nodes depth-first in file order, a node's own
//   mesh before its children. World = parent * local; local from `matrix` or T * R * S.
// - Triangles are numbered in that order: node by node, each mesh's primitives in order, each
//   primitive's triangles in index order. Only TRIANGLES primitives are loaded; points, lines,
//   strips and fans are skipped and counted in Scene::skipped_primitives (per instance).
//   Where a node's world transform mirrors (negative determinant), vertices 1 and 2 of each
//   triangle are swapped so that front faces stay counter-clockwise in world space, as the
//   glTF spec asks; the triangle order is unchanged.
// - Normals: world-space (inverse transpose), unit length; a primitive without NORMAL gets its
//   triangles' geometric normals when any other primitive has normals, and Scene::normals
//   stays empty when none has.
// - Accessors: every component type, normalized integers, sparse accessors
//   (gltf_accessors.h); integer POSITION/NORMAL where the file declares
//   KHR_mesh_quantization; KHR_draco_mesh_compression (gltf_draco.h) and
//   EXT_meshopt_compression (gltf_meshopt.h), decoded as the file is parsed.
// - The still pose: morph targets at the node's weights (else the mesh's); a skinned mesh
//   follows its joints' world matrices times their inverse bind matrices, weighted by
//   JOINTS_n/WEIGHTS_n normalised to sum 1, and ignores its own node's transform (glTF).
// - Triangles with a NaN/Inf world coordinate are dropped (Scene::dropped_degenerate).
// - Materials: Scene::materials[i] is glTF material i; a "default" Material{} is appended once
//   if some primitive has no material. Images, samplers, textures and the material's
//   texture slots as gltf_textures.h says: images kept encoded, decoded by host/texture.
// - TEXCOORD_0/1 and COLOR_0 per triangle vertex (gltf_vertex_attributes.h).
// - Camera: the first camera node in traversal order (or the one named by LoadOptions); its
//   world matrix keeps the translation, with the rotation part orthonormalised (scale and
//   shear removed) so that it is a pure camera-to-world rigid transform.
// - Lights: KHR_lights_punctual on traversed nodes, in traversal order.
// - Animation: GltfDocument::flatten takes a pose (node_pose.h) that replaces animated nodes'
//   TRS and morph weights; skins, cameras and lights follow the posed nodes.
// - Security: external files (buffers, images) must lie inside the scene's folder: absolute
//   URIs, ".." components and symbolic links leading out are rejected; data URIs over
//   256 MiB are rejected before decoding.
//
// Every failure throws gridrt::SceneError with a one-line message naming the file (or label)
// and the element, e.g. "scene.glb: accessor 3: index 912 out of range for 453 vertices".
#pragma once
#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "node_pose.h"
#include "scene.h"

namespace tinygltf {
class Model;
}

namespace gridrt {

struct GltfLoadOptions {
  // Empty: the first camera in traversal order. A number N: the N-th camera node in
  // traversal order (from 0). Otherwise the first camera node whose camera name or node
  // name equals this. A SceneError lists the available cameras if none does.
  std::string camera_name;
};

// Loads a .gltf or .glb file (binary when the extension is .glb or the data begins with the
// "glTF" magic). External files are looked up next to `path`.
Scene loadGltfFile(const std::string& path, const GltfLoadOptions& options = {});

// Loads glTF from memory: binary if it begins with "glTF", JSON otherwise. External files are
// looked up in `base_dir`; with an empty base_dir no external file may be read. `label` names
// the data in messages (a file name, or e.g. "fuzz input").
Scene loadGltfFromMemory(const unsigned char* data, size_t size, const std::string& base_dir,
                         const std::string& label, const GltfLoadOptions& options = {});

// A glTF document parsed (and its files read) once, flattened into a Scene at any pose:
// an animated scene's frames (gltf_animation.h samples the poses). Copies share the model.
class GltfDocument {
 public:
  // As loadGltfFile and loadGltfFromMemory read them; every parse failure throws SceneError.
  static GltfDocument fromFile(const std::string& path);
  static GltfDocument fromMemory(const unsigned char* data, size_t size,
                                 const std::string& base_dir, const std::string& label);
  // The scene with `pose` (one entry per node) in place of the file's translation,
  // rotation, scale and morph weights where it sets them; null: the still pose, as
  // loadGltfFile gives it. The same document and pose give the same scene bit for bit as
  // a file whose nodes hold the pose's values.
  Scene flatten(const GltfLoadOptions& options = {}, const ScenePose* pose = nullptr) const;
  const tinygltf::Model& model() const { return *model_; }
  const std::string& label() const { return label_; }

 private:
  GltfDocument(std::shared_ptr<const tinygltf::Model> model, std::string label,
               std::vector<std::string> warnings);
  std::shared_ptr<const tinygltf::Model> model_;
  std::string label_;
  std::vector<std::string> parse_warnings_;  // tinygltf's, repeated in every flattened scene
};

}  // namespace gridrt
