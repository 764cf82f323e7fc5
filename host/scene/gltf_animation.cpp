#include "gltf_animation.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <optional>

#include "errors.h"
#include "gltf_accessors.h"

namespace gridrt {
namespace {

using gltf::fail;

std::string shortNumber(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", v);
  return text;
}

std::string quotedName(const std::string& name) { return name.empty() ? "" : " '" + name + "'"; }

const char* propertyName(AnimatedProperty p) {
  switch (p) {
    case AnimatedProperty::Translation:
      return "translation";
    case AnimatedProperty::Rotation:
      return "rotation";
    case AnimatedProperty::Scale:
      return "scale";
    default:
      return "weights";
  }
}

std::optional<AnimatedProperty> propertyOf(const std::string& path) {
  if (path == "translation") return AnimatedProperty::Translation;
  if (path == "rotation") return AnimatedProperty::Rotation;
  if (path == "scale") return AnimatedProperty::Scale;
  if (path == "weights") return AnimatedProperty::Weights;
  return std::nullopt;
}

// Reads an accessor of a sampler; its own failures are reported as the sampler's.
gltf::AccessorData samplerAccessor(const tinygltf::Model& model, int index, const char* role,
                                   const std::string& label, const std::string& where) {
  if (index < 0 || size_t(index) >= model.accessors.size())
    fail(label, where + ": " + role + " accessor " + std::to_string(index) + " does not exist (" +
                    std::to_string(model.accessors.size()) + " accessors)");
  try {
    return gltf::readAccessor(model, index, label);
  } catch (const SceneError& e) {
    std::string what = e.what();
    if (what.compare(0, label.size() + 2, label + ": ") == 0) what.erase(0, label.size() + 2);
    fail(label, where + ": " + role + " " + what);
  }
}

// A sampler's keys as read (the values not yet split by channel).
struct SamplerKeys {
  Interpolation interpolation = Interpolation::Linear;
  std::vector<double> times;
  gltf::AccessorData output;
};

SamplerKeys readSampler(const tinygltf::Model& model, const tinygltf::AnimationSampler& s,
                        const std::string& label, const std::string& where) {
  SamplerKeys keys;
  if (s.interpolation == "LINEAR")
    keys.interpolation = Interpolation::Linear;
  else if (s.interpolation == "STEP")
    keys.interpolation = Interpolation::Step;
  else if (s.interpolation == "CUBICSPLINE")
    keys.interpolation = Interpolation::CubicSpline;
  else
    fail(label,
         where + ": interpolation '" + s.interpolation + "' is not LINEAR, STEP or CUBICSPLINE");
  const gltf::AccessorData input = samplerAccessor(model, s.input, "input", label, where);
  if (input.type != TINYGLTF_TYPE_SCALAR || input.component_type != TINYGLTF_COMPONENT_TYPE_FLOAT)
    fail(label, where + ": input times must be FLOAT SCALAR, not " +
                    gltf::componentName(input.component_type) + " " + gltf::typeName(input.type));
  if (input.count == 0) fail(label, where + ": input has no key times");
  keys.times.assign(input.values.begin(), input.values.end());
  for (size_t k = 0; k < keys.times.size(); ++k) {
    if (!std::isfinite(keys.times[k]))
      fail(label, where + ": input time " + std::to_string(k) + " is " +
                      (std::isnan(keys.times[k]) ? "NaN" : "infinite"));
    if (k > 0 && !(keys.times[k] > keys.times[k - 1]))
      fail(label, where + ": input times do not increase: time " + std::to_string(k) + " (" +
                      shortNumber(keys.times[k]) + ") after time " + std::to_string(k - 1) + " (" +
                      shortNumber(keys.times[k - 1]) + ")");
  }
  keys.output = samplerAccessor(model, s.output, "output", label, where);
  for (size_t i = 0; i < keys.output.values.size(); ++i)
    if (!std::isfinite(keys.output.values[i]))
      fail(label, where + ": output value " + std::to_string(i) + " is " +
                      (std::isnan(keys.output.values[i]) ? "NaN" : "infinite"));
  return keys;
}

// The morph target count of a node's mesh (the first primitive's; glTF asks all to agree).
size_t morphTargetCount(const tinygltf::Model& model, const tinygltf::Node& node) {
  if (node.mesh < 0 || size_t(node.mesh) >= model.meshes.size()) return 0;
  const tinygltf::Mesh& mesh = model.meshes[size_t(node.mesh)];
  return mesh.primitives.empty() ? 0 : mesh.primitives[0].targets.size();
}

// The track of a channel aimed at `property` of `node`, its output checked against what
// that property takes.
KeyframeTrack channelTrack(const tinygltf::Model& model, const SamplerKeys& keys,
                           AnimatedProperty property, const tinygltf::Node& node,
                           const std::string& label, const std::string& where) {
  KeyframeTrack track;
  track.interpolation = keys.interpolation;
  track.quaternion = property == AnimatedProperty::Rotation;
  track.times = keys.times;
  const gltf::AccessorData& out = keys.output;
  const std::string name = propertyName(property);
  // The accessor type and how many of its elements one key's value takes.
  int type = TINYGLTF_TYPE_VEC3;
  size_t elements_per_value = 1;
  if (property == AnimatedProperty::Rotation) type = TINYGLTF_TYPE_VEC4;
  if (property == AnimatedProperty::Weights) {
    type = TINYGLTF_TYPE_SCALAR;
    elements_per_value = morphTargetCount(model, node);
    if (elements_per_value == 0) fail(label, where + ": weights of a node without morph targets");
  }
  const bool float_only =
      property == AnimatedProperty::Translation || property == AnimatedProperty::Scale;
  const bool component_ok =
      out.component_type == TINYGLTF_COMPONENT_TYPE_FLOAT || (!float_only && out.normalized);
  if (out.type != type || !component_ok)
    fail(label, where + ": " + name + " output must be " +
                    (float_only ? "FLOAT " : "FLOAT or normalized ") + gltf::typeName(type) +
                    ", not " + gltf::componentName(out.component_type) + " " +
                    gltf::typeName(out.type) + (out.normalized ? " normalized" : ""));
  const size_t groups = keys.interpolation == Interpolation::CubicSpline ? 3 : 1;
  const size_t needed = keys.times.size() * groups * elements_per_value;
  if (out.count != needed)
    fail(label, where + ": input has " + std::to_string(keys.times.size()) +
                    " key times but output has " + std::to_string(out.count) + " elements (" +
                    (groups == 3 ? "CUBICSPLINE " : "") + name + " needs " +
                    std::to_string(needed) + ")");
  track.width = property == AnimatedProperty::Weights ? int(elements_per_value) : out.components;
  track.values.assign(out.values.begin(), out.values.end());
  if (track.quaternion)  // a zero quaternion is no rotation (cubic tangents may be zero)
    for (size_t k = 0; k < track.times.size(); ++k) {
      const size_t first = (k * groups + (groups == 3 ? 1 : 0)) * 4;
      if (std::all_of(track.values.begin() + long(first), track.values.begin() + long(first + 4),
                      [](double v) { return v == 0.0; }))
        fail(label, where + ": rotation key " + std::to_string(k) + " is a zero quaternion");
    }
  return track;
}

}  // namespace

std::vector<Animation> readAnimations(const tinygltf::Model& model, const std::string& label,
                                      std::vector<std::string>& warnings) {
  std::vector<Animation> out;
  for (size_t a = 0; a < model.animations.size(); ++a) {
    const tinygltf::Animation& source = model.animations[a];
    const std::string animation = "animation " + std::to_string(a) + quotedName(source.name);
    Animation anim;
    anim.name = source.name;
    std::vector<std::optional<SamplerKeys>> samplers(source.samplers.size());
    bool any_key = false;
    for (size_t c = 0; c < source.channels.size(); ++c) {
      const tinygltf::AnimationChannel& channel = source.channels[c];
      const int s = channel.sampler;
      std::string where = animation + " channel " + std::to_string(c);
      if (s < 0 || size_t(s) >= source.samplers.size())
        fail(label, where + ": sampler " + std::to_string(s) + " does not exist (" +
                        std::to_string(source.samplers.size()) + " samplers)");
      where = animation + " sampler " + std::to_string(s) + " (channel " + std::to_string(c) + ")";
      const std::optional<AnimatedProperty> property = propertyOf(channel.target_path);
      if (!property || channel.target_node < 0) {
        warnings.push_back(where + ": " +
                           (property ? std::string("no target node")
                                     : "target path '" + channel.target_path + "'") +
                           " is not supported; ignored");
        continue;
      }
      if (size_t(channel.target_node) >= model.nodes.size())
        fail(label, where + ": target node " + std::to_string(channel.target_node) +
                        " does not exist (" + std::to_string(model.nodes.size()) + " nodes)");
      const tinygltf::Node& node = model.nodes[size_t(channel.target_node)];
      const std::string target = "node " + std::to_string(channel.target_node) +
                                 quotedName(node.name) + " " + propertyName(*property);
      if (!node.matrix.empty() && *property != AnimatedProperty::Weights)
        fail(label, where + ": targets " + target +
                        " of a node with a matrix (glTF allows only TRS on animated nodes)");
      for (const AnimationChannel& earlier : anim.channels)
        if (earlier.node == channel.target_node && earlier.property == *property)
          fail(label, where + ": " + target + " is animated twice by this animation");
      if (!samplers[size_t(s)])
        samplers[size_t(s)] = readSampler(model, source.samplers[size_t(s)], label, where);
      AnimationChannel parsed;
      parsed.node = channel.target_node;
      parsed.property = *property;
      parsed.track = channelTrack(model, *samplers[size_t(s)], *property, node, label, where);
      const double first = parsed.track.times.front(), last = parsed.track.times.back();
      anim.start = any_key ? std::min(anim.start, first) : first;
      anim.end = any_key ? std::max(anim.end, last) : last;
      any_key = true;
      anim.channels.push_back(std::move(parsed));
    }
    out.push_back(std::move(anim));
  }
  for (std::string& w : warnings) w = gltf::oneLine(w);
  return out;
}

std::vector<size_t> chooseAnimations(const std::vector<Animation>& animations,
                                     const std::string& wanted, const std::string& label) {
  std::vector<size_t> all(animations.size());
  for (size_t a = 0; a < all.size(); ++a) all[a] = a;
  if (wanted.empty()) return all;
  if (animations.empty())
    throw UsageError(
        gltf::oneLine(label + ": --animation '" + wanted + "': the scene has no animations"));
  const bool numeric =
      std::all_of(wanted.begin(), wanted.end(), [](unsigned char c) { return std::isdigit(c); }) &&
      wanted.size() < 9;
  std::string available;
  for (size_t a = 0; a < animations.size(); ++a) {
    if (numeric ? std::stoul(wanted) == a : animations[a].name == wanted) return {a};
    available += (available.empty() ? "" : ", ") + std::to_string(a) +
                 (animations[a].name.empty() ? " (unnamed)" : " = '" + animations[a].name + "'");
  }
  throw UsageError(
      gltf::oneLine(label + ": animation '" + wanted + "' not found; available: " + available));
}

ScenePose poseAt(const std::vector<Animation>& animations, const std::vector<size_t>& playing,
                 size_t node_count, double t) {
  ScenePose pose(node_count);
  for (size_t a : playing)
    for (const AnimationChannel& channel : animations[a].channels) {
      const std::vector<double> v = sampleTrack(channel.track, t);
      NodePose& node = pose[size_t(channel.node)];
      switch (channel.property) {
        case AnimatedProperty::Translation:
          node.translation = glm::dvec3(v[0], v[1], v[2]);
          break;
        case AnimatedProperty::Rotation:
          node.rotation = glm::dvec4(v[0], v[1], v[2], v[3]);
          break;
        case AnimatedProperty::Scale:
          node.scale = glm::dvec3(v[0], v[1], v[2]);
          break;
        case AnimatedProperty::Weights:
          node.weights = v;
          break;
      }
    }
  return pose;
}

}  // namespace gridrt
