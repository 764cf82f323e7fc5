// What an animation sets on the nodes of a glTF document at one moment. The loader
// flattens the node tree with these in place of the file's values (gltf_loader.h);
// a property left unset keeps what the file says.
#pragma once
#include <glm/glm.hpp>
#include <optional>
#include <vector>

namespace gridrt {

struct NodePose {
  std::optional<glm::dvec3> translation;
  std::optional<glm::dvec4> rotation;  // quaternion x, y, z, w
  std::optional<glm::dvec3> scale;
  std::optional<std::vector<double>> weights;  // one per morph target of the node's mesh

  bool movesTransform() const { return translation || rotation || scale; }
};

// One NodePose per node of the document, in node order.
using ScenePose = std::vector<NodePose>;

}  // namespace gridrt
