// An animated glTF scene for the tests, written here: a floor, a cube that turns (LINEAR
// rotation, slerp) and grows (STEP scale), a quad with two morph targets (CUBICSPLINE
// weights), a strip skinned to two joints (the upper joint turns), a point light and the
// camera moving (LINEAR translations). Two animations, "Move" (camera, light, cube) and
// "Deform" (morph weights, joint), over 0..1 s. The same scene with any pose baked into
// its nodes and no animations is bakedJson: what the loader must flatten identically.
#pragma once
#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "gltf_document_builder.h"
#include "node_pose.h"

namespace gridrt::test {

struct AnimatedTestScene {
  GltfDocumentBuilder buffer;
  std::vector<TestNode> nodes;  // the still pose
  std::string rest;             // scenes, meshes, skins, cameras, lights
  std::string animations;       // "\"animations\":[...]"

  std::string animatedJson() const {
    return buffer.json(nodesJson(nodes) + "," + rest + "," + animations);
  }
  // The scene with each node's values replaced by the pose's, and no animations.
  std::string bakedJson(const ScenePose& pose) const {
    std::vector<TestNode> baked = nodes;
    for (size_t n = 0; n < baked.size() && n < pose.size(); ++n) {
      if (pose[n].translation) baked[n].translation = pose[n].translation;
      if (pose[n].rotation) baked[n].rotation = pose[n].rotation;
      if (pose[n].scale) baked[n].scale = pose[n].scale;
      if (pose[n].weights) baked[n].weights = pose[n].weights;
    }
    return buffer.json(nodesJson(baked) + "," + rest);
  }
};

// Node indices of the scene.
enum AnimatedTestNode : int {
  kCameraNode = 0,
  kFloorNode,
  kCubeNode,
  kMorphNode,
  kLightNode,
  kSkinNode,
  kRootJoint,
  kTipJoint
};

inline std::vector<float> quadTriangles(glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 d) {
  return {a.x, a.y, a.z, b.x, b.y, b.z, c.x, c.y, c.z, a.x, a.y, a.z, c.x, c.y, c.z, d.x, d.y, d.z};
}

inline std::vector<float> unitCubeTriangles() {
  std::vector<float> out;
  auto face = [&](glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 d) {
    const std::vector<float> q = quadTriangles(a, b, c, d);
    out.insert(out.end(), q.begin(), q.end());
  };
  const float h = 0.5f;
  face({-h, -h, h}, {h, -h, h}, {h, h, h}, {-h, h, h});
  face({h, -h, -h}, {-h, -h, -h}, {-h, h, -h}, {h, h, -h});
  face({h, -h, h}, {h, -h, -h}, {h, h, -h}, {h, h, h});
  face({-h, -h, -h}, {-h, -h, h}, {-h, h, h}, {-h, h, -h});
  face({-h, h, h}, {h, h, h}, {h, h, -h}, {-h, h, -h});
  face({-h, -h, -h}, {h, -h, -h}, {h, -h, h}, {-h, -h, h});
  return out;
}

inline AnimatedTestScene makeAnimatedTestScene() {
  AnimatedTestScene s;
  GltfDocumentBuilder& b = s.buffer;
  const int floor =
      b.floats(quadTriangles({-4, -1, 2}, {4, -1, 2}, {4, -1, -4}, {-4, -1, -4}), "VEC3");
  const int cube = b.floats(unitCubeTriangles(), "VEC3");
  // The morph quad and its targets: target 0 lifts the top edge, target 1 pushes it back.
  const int morph = b.floats(
      quadTriangles({-0.5f, -0.5f, 0}, {0.5f, -0.5f, 0}, {0.5f, 0.5f, 0}, {-0.5f, 0.5f, 0}),
      "VEC3");
  const int lift =
      b.floats({0, 0, 0, 0, 0, 0, 0, 0.8f, 0, 0, 0, 0, 0, 0.8f, 0, 0, 0.8f, 0}, "VEC3");
  const int push =
      b.floats({0, 0, 0, 0, 0, 0, 0, 0, -0.6f, 0, 0, 0, 0, 0, -0.6f, 0, 0, -0.6f}, "VEC3");
  // The skinned strip in its bind pose (world space): two quads from y = -1 to 1 at z = -1;
  // bottom vertices on the root joint, middle ones half and half, top ones on the tip.
  std::vector<float> strip =
      quadTriangles({-0.3f, -1, -1}, {0.3f, -1, -1}, {0.3f, 0, -1}, {-0.3f, 0, -1});
  const std::vector<float> upper =
      quadTriangles({-0.3f, 0, -1}, {0.3f, 0, -1}, {0.3f, 1, -1}, {-0.3f, 1, -1});
  strip.insert(strip.end(), upper.begin(), upper.end());
  std::vector<uint8_t> joints;
  std::vector<float> weights;
  for (size_t v = 0; v < strip.size() / 3; ++v) {
    const float y = strip[3 * v + 1];
    joints.insert(joints.end(), {0, 1, 0, 0});
    const float tip = y < -0.5f ? 0.0f : y > 0.5f ? 1.0f : 0.5f;
    weights.insert(weights.end(), {1.0f - tip, tip, 0, 0});
  }
  const int strip_positions = b.floats(strip, "VEC3");
  const int strip_joints = b.bytes(joints, "VEC4");
  const int strip_weights = b.floats(weights, "VEC4");
  // Inverse bind matrices: the joints' bind worlds are translations by (0, -1, -1) and
  // (0, 0, -1).
  std::vector<float> ibm(32, 0.0f);
  for (int m = 0; m < 2; ++m)
    for (int d = 0; d < 4; ++d) ibm[size_t(m * 16 + d * 5)] = 1.0f;
  ibm[13] = 1.0f, ibm[14] = 1.0f;  // root: translation (0, 1, 1)
  ibm[16 + 14] = 1.0f;             // tip: translation (0, 0, 1)
  const int inverse_bind = b.floats(ibm, "MAT4");

  s.nodes.resize(8);
  auto node = [&](int index, const std::string& members,
                  std::optional<glm::dvec3> translation = std::nullopt) {
    s.nodes[size_t(index)].members = members;
    s.nodes[size_t(index)].translation = translation;
  };
  node(kCameraNode, "\"camera\":0", glm::dvec3(0, 1, 7));
  node(kFloorNode, "\"mesh\":0");
  node(kCubeNode, "\"mesh\":1", glm::dvec3(-1.5, 0, 0));
  node(kMorphNode, "\"mesh\":2", glm::dvec3(1.5, 0, 0));
  s.nodes[kMorphNode].weights = std::vector<double>{0.25, 0};
  node(kLightNode, "\"extensions\":{\"KHR_lights_punctual\":{\"light\":0}}", glm::dvec3(-2, 3, 3));
  node(kSkinNode, "\"mesh\":3,\"skin\":0", glm::dvec3(50, 0, 0));  // ignored: skinned
  node(kRootJoint, "\"children\":[7]", glm::dvec3(0, -1, -1));
  node(kTipJoint, "", glm::dvec3(0, 1, 0));
  s.nodes[kTipJoint].rotation = glm::dvec4(0, 0, 0, 1);
  auto mesh = [](int position, const std::string& more = "") {
    return "{\"primitives\":[{\"attributes\":{\"POSITION\":" + std::to_string(position) + more +
           "}}]}";
  };
  const std::string morph_mesh =
      "{\"primitives\":[{\"attributes\":{\"POSITION\":" + std::to_string(morph) +
      "},\"targets\":[{\"POSITION\":" + std::to_string(lift) +
      "},{\"POSITION\":" + std::to_string(push) + "}]}],\"weights\":[0,0]}";
  s.rest =
      "\"scene\":0,\"scenes\":[{\"nodes\":[0,1,2,3,4,5,6]}],\"meshes\":[" + mesh(floor) + "," +
      mesh(cube) + "," + morph_mesh + "," +
      mesh(strip_positions, ",\"JOINTS_0\":" + std::to_string(strip_joints) +
                                ",\"WEIGHTS_0\":" + std::to_string(strip_weights)) +
      "],\"skins\":[{\"joints\":[6,7],\"inverseBindMatrices\":" + std::to_string(inverse_bind) +
      "}],\"cameras\":[{\"type\":\"perspective\",\"perspective\":{\"yfov\":0.8,"
      "\"znear\":0.1}}],\"extensionsUsed\":[\"KHR_lights_punctual\"],\"extensions\":{"
      "\"KHR_lights_punctual\":{\"lights\":[{\"type\":\"point\",\"intensity\":60}]}}";

  // The keys.
  const int t01 = b.floats({0, 1}, "SCALAR");
  const int t0h = b.floats({0, 0.5f}, "SCALAR");
  const int camera_path = b.floats({0, 1, 7, 0.5f, 1.2f, 6.5f}, "VEC3");
  const int light_path = b.floats({-2, 3, 3, 2, 3, 3}, "VEC3");
  // The cube turns by 120 degrees about +y: slerp from identity.
  const float half = float(60.0 * 3.14159265358979323846 / 180.0);
  const int cube_turn = b.floats({0, 0, 0, 1, 0, std::sin(half), 0, std::cos(half)}, "VEC4");
  const int cube_grow = b.floats({1, 1, 1, 1.3f, 0.8f, 1.3f}, "VEC3");
  // CUBICSPLINE weights: per key in-tangents (2), values (2), out-tangents (2).
  const int morph_weights =
      b.floats({0, 0, 0.25f, 0, 1.5f, 0.5f, -0.5f, 1, 1, 0.5f, 0, 0}, "SCALAR");
  // The tip joint bends by 60 degrees about +z.
  const float bend = float(30.0 * 3.14159265358979323846 / 180.0);
  const int tip_bend = b.floats({0, 0, 0, 1, 0, 0, std::sin(bend), std::cos(bend)}, "VEC4");
  auto sampler = [](int input, int output, const char* interpolation) {
    return "{\"input\":" + std::to_string(input) + ",\"output\":" + std::to_string(output) +
           ",\"interpolation\":\"" + interpolation + "\"}";
  };
  auto channel = [](int sampler_index, int node, const char* path) {
    return "{\"sampler\":" + std::to_string(sampler_index) +
           ",\"target\":{\"node\":" + std::to_string(node) + ",\"path\":\"" + path + "\"}}";
  };
  s.animations =
      "\"animations\":[{\"name\":\"Move\",\"samplers\":[" + sampler(t01, camera_path, "LINEAR") +
      "," + sampler(t01, light_path, "LINEAR") + "," + sampler(t01, cube_turn, "LINEAR") + "," +
      sampler(t0h, cube_grow, "STEP") + "],\"channels\":[" +
      channel(0, kCameraNode, "translation") + "," + channel(1, kLightNode, "translation") + "," +
      channel(2, kCubeNode, "rotation") + "," + channel(3, kCubeNode, "scale") +
      "]},{\"name\":\"Deform\",\"samplers\":[" + sampler(t01, morph_weights, "CUBICSPLINE") + "," +
      sampler(t01, tip_bend, "LINEAR") + "],\"channels\":[" + channel(0, kMorphNode, "weights") +
      "," + channel(1, kTipJoint, "rotation") + "]}]";
  return s;
}

}  // namespace gridrt::test
