// glTF 2.0 animations: read and checked once, then sampled at any time into a ScenePose
// (node_pose.h) that the loader flattens (gltf_loader.h).
//
// - Channels on a node's translation, rotation, scale and morph-target weights; STEP,
//   LINEAR (slerp along the shorter arc for rotations) and CUBICSPLINE
//   (keyframe_interpolation.h). Before its first key and after its last a channel holds
//   the first or last value.
// - Several animations play together (the default) or one is chosen (chooseAnimations);
//   where two playing channels set the same property of a node, the later animation in
//   file order wins.
// - Refused, each with one line naming the file, the animation, its sampler or channel
//   and the problem (SceneError): input and output counts that disagree, times that do not
//   increase strictly, NaN or infinite keys, channels aimed at nodes that do not exist,
//   at a node with a `matrix` (glTF forbids it), or at the weights of a node without
//   morph targets; unknown interpolations; two channels of one animation on the same
//   property. Ignored with a warning: channels without a target node or with a path other
//   than the four (KHR_animation_pointer).
#pragma once
#include <tiny_gltf.h>

#include <cstddef>
#include <string>
#include <vector>

#include "keyframe_interpolation.h"
#include "node_pose.h"

namespace gridrt {

enum class AnimatedProperty { Translation, Rotation, Scale, Weights };

struct AnimationChannel {
  int node = -1;
  AnimatedProperty property = AnimatedProperty::Translation;
  KeyframeTrack track;
};

struct Animation {
  std::string name;  // as in the file (may be empty)
  std::vector<AnimationChannel> channels;
  double start = 0.0, end = 0.0;  // the first and last key time of any channel
};

// Every animation of `model`, checked; `label` names the file in messages. Warnings (ignored
// channels) are appended to `warnings`.
std::vector<Animation> readAnimations(const tinygltf::Model& model, const std::string& label,
                                      std::vector<std::string>& warnings);

// The animations that play: all of them for an empty `wanted`; else the one whose index
// (a number) or name it is. Throws UsageError listing the animations when none is.
std::vector<size_t> chooseAnimations(const std::vector<Animation>& animations,
                                     const std::string& wanted, const std::string& label);

// The pose of `node_count` nodes at time t (seconds) with the `playing` animations.
ScenePose poseAt(const std::vector<Animation>& animations, const std::vector<size_t>& playing,
                 size_t node_count, double t);

}  // namespace gridrt
