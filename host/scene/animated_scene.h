// A scene to render at any time: a glTF document with the animations that play, posed
// and flattened anew for each time asked (the document is parsed once).
#pragma once
#include <string>
#include <vector>

#include "gltf_animation.h"
#include "gltf_loader.h"
#include "scene.h"

namespace gridrt {

class AnimatedScene {
 public:
  // The document's animations, read and checked (gltf_animation.h): all of them play for
  // an empty `animation`, else the one of that index or name. Throws SceneError for a bad
  // animation, UsageError for an unknown `animation`.
  AnimatedScene(GltfDocument document, GltfLoadOptions options, const std::string& animation);

  // Whether any playing animation has a channel (else every time gives the still pose).
  bool moves() const;
  // The scene as written, without animation.
  Scene still() const;
  // The scene posed at t seconds.
  Scene at(double t) const;
  // The animations of the file (all, playing or not) and the ignored channels' warnings.
  const std::vector<Animation>& animations() const { return animations_; }
  const std::vector<std::string>& warnings() const { return warnings_; }

 private:
  GltfDocument document_;
  GltfLoadOptions options_;
  std::vector<Animation> animations_;
  std::vector<size_t> playing_;
  std::vector<std::string> warnings_;
};

}  // namespace gridrt
