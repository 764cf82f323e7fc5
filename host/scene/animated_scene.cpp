#include "animated_scene.h"

#include <tiny_gltf.h>

#include <utility>

namespace gridrt {

AnimatedScene::AnimatedScene(GltfDocument document, GltfLoadOptions options,
                             const std::string& animation)
    : document_(std::move(document)), options_(std::move(options)) {
  animations_ = readAnimations(document_.model(), document_.label(), warnings_);
  playing_ = chooseAnimations(animations_, animation, document_.label());
}

bool AnimatedScene::moves() const {
  for (size_t a : playing_)
    if (!animations_[a].channels.empty()) return true;
  return false;
}

Scene AnimatedScene::still() const { return document_.flatten(options_); }

Scene AnimatedScene::at(double t) const {
  const ScenePose pose = poseAt(animations_, playing_, document_.model().nodes.size(), t);
  return document_.flatten(options_, &pose);
}

}  // namespace gridrt
