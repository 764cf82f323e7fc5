// Where a run's scene comes from and how it is framed: the built-in default scene, a mesh
// file, a glTF document (still, or posed for a time), and the camera the options choose.
// The command line, the viewer and the Python module load scenes through these.
#pragma once
#include <optional>
#include <string>
#include <vector>

#include "animated_scene.h"
#include "options.h"
#include "scene.h"

namespace gridrt {

// Where the frames come from: a fixed scene (the built-in one, or a file in its still
// pose), or a glTF document with its animations, posed for each frame.
struct SceneSource {
  std::optional<AnimatedScene> animated;
  std::vector<std::string> warnings;  // about the animation, said once
};

// Loads o.scene into first_scene, posed at first_time (none: the still pose, as written).
// Animations are read (and checked) only when a time is asked for.
SceneSource loadScene(const Options& o, const std::optional<double>& first_time,
                      Scene& first_scene);

// The camera of `scene` (or one framing `framing`, a scene without a camera's box) with
// --look-at and --fov applied.
Camera chooseCamera(const Options& o, const Scene& scene, const Bounds& framing);

// The image size: as given, or with no --width/--height (and no --crop, which is placed in
// the given size) from the scene camera's aspectRatio at the default height.
Options sizedForCamera(const Options& given, const Camera& camera);

}  // namespace gridrt
