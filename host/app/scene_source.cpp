#include "scene_source.h"

#include <algorithm>
#include <cmath>

#include "camera_rays.h"
#include "default_scene.h"
#include "errors.h"
#include "gltf_loader.h"
#include "mesh_import.h"
#include "standard_input_scene.h"
#include "standard_streams.h"
#include "texture_decoding.h"

namespace gridrt {

namespace {

// The built-in scene is not loaded through the glTF loader, so --camera is checked here.
Scene loadDefaultScene(const Options& o) {
  Scene scene = makeDefaultScene();
  if (!o.camera_name.empty() && o.camera_name != scene.camera.name && o.camera_name != "0")
    throw UsageError("--camera: the built-in default scene has no camera '" + o.camera_name +
                     "' (its only camera is 0 = '" + scene.camera.name + "')");
  return scene;
}

}  // namespace

SceneSource loadScene(const Options& o, const std::optional<double>& first_time,
                      Scene& first_scene) {
  SceneSource source;
  const bool posed = first_time.has_value();
  if (o.scene.empty()) {
    if (!o.animation.empty())
      throw UsageError("--animation '" + o.animation + "': the built-in scene has no animations");
    first_scene = loadDefaultScene(o);
    if (posed)
      source.warnings.push_back(
          "the built-in scene has no animations: --time/--frames "
          "render it as it is");
    return source;
  }
  if (isImportedMeshFile(o.scene)) {
    // Geometry and material colours only: no cameras, animations or textures (mesh_import.h).
    if (!o.camera_name.empty())
      throw UsageError("--camera '" + o.camera_name + "': " + o.scene +
                       " is read without cameras (the view frames the scene)");
    if (!o.animation.empty())
      throw UsageError("--animation '" + o.animation + "': " + o.scene +
                       " is read without animations");
    first_scene = importMeshFile(o.scene);
    if (posed)
      source.warnings.push_back(o.scene +
                                " is read without animations: --time/--frames "
                                "render it as it is");
    return source;
  }
  GltfDocument document =
      o.scene == kStandardInput ? readStandardInputScene() : GltfDocument::fromFile(o.scene);
  const size_t animations = document.model().animations.size();
  if (!posed) {
    if (animations > 0)
      source.warnings.push_back("the scene has " + std::to_string(animations) +
                                " animation(s); rendered in its still pose (--time or --frames "
                                "poses it)");
    first_scene = document.flatten(GltfLoadOptions{o.camera_name});
    decodeTextures(first_scene);  // the loader keeps its images encoded
    return source;
  }
  source.animated.emplace(std::move(document), GltfLoadOptions{o.camera_name}, o.animation);
  for (const auto& w : source.animated->warnings()) source.warnings.push_back(w);
  if (!source.animated->moves())
    source.warnings.push_back(
        "the scene has no animation channels: --time/--frames render its "
        "still pose");
  first_scene = source.animated->at(*first_time);
  decodeTextures(first_scene);  // once: every frame's pose reads the same images
  return source;
}

Camera chooseCamera(const Options& o, const Scene& scene, const Bounds& framing) {
  Camera camera = scene.has_camera ? scene.camera : defaultCamera(framing);
  if (o.eye) {
    // Moved and turned, the camera keeps its projection (an orthographic one stays so).
    Camera looked = lookAtCamera(*o.eye, *o.target, camera.yfov);
    looked.orthographic = camera.orthographic;
    looked.xmag = camera.xmag, looked.ymag = camera.ymag, looked.aspect = camera.aspect;
    camera = looked;
  }
  if (o.fov_degrees) {
    camera.orthographic = false;
    camera.yfov = *o.fov_degrees * 3.14159265f / 180.0f;
  }
  return camera;
}

Options sizedForCamera(const Options& given, const Camera& camera) {
  Options o = given;
  if (!o.size_given && !o.crop && camera.aspect > 0.0f && std::isfinite(camera.aspect))
    o.width = int(std::clamp(std::lround(double(o.height) * camera.aspect), 1L, 65536L));
  return o;
}

}  // namespace gridrt
