#include "image_render.h"

#include "errors.h"
#include "frame_render.h"
#include "image_fits.h"
#include "layered_image.h"
#include "prepared_triangles.h"
#include "python_options.h"
#include "scene_source.h"
#include "thread_count.h"

namespace gridrt {

RenderedImage renderImage(const std::vector<std::string>& arguments, const Scene* scene) {
  const Options given = pythonOptions(arguments);
  if (scene && !given.scene.empty())
    throw UsageError("a Scene and a scene path: pass one of them");
  if (scene && given.time)
    throw UsageError("time: pose a file's animation by passing its path, not a Scene");
  checkImageFitsHost(given);
  const ThreadLimit thread_limit(given.threads);
  RenderedImage result;
  result.warnings = given.warnings;

  Scene loaded;
  SceneSource source;
  if (!scene) {
    source = loadScene(given, given.time, loaded);
    scene = &loaded;
    result.warnings.insert(result.warnings.end(), source.warnings.begin(), source.warnings.end());
  }
  result.warnings.insert(result.warnings.end(), scene->warnings.begin(), scene->warnings.end());
  // As the command line frames it: a scene without a camera on its still pose.
  const Bounds framing =
      scene->has_camera ? Bounds{}
                        : sceneBounds(source.animated ? source.animated->still() : *scene);
  const Options o = sizedForCamera(given, chooseCamera(given, *scene, framing));
  if (o.width != given.width) checkImageFitsHost(o);
  ClRuntime runtime(o.device);
  checkImageFitsDevice(o, runtime.info());
  const FrameResult frame = renderScene(o, runtime, *scene, chooseCamera(o, *scene, framing),
                                        [](double) {}, false);
  const LayeredImage image = outputImage(o, frame.frame);

  result.width = image.width;
  result.height = image.height;
  result.channels = int(image.channels.size());
  const size_t pixels = size_t(image.width) * size_t(image.height);
  result.pixels.resize(pixels * image.channels.size());
  for (size_t c = 0; c < image.channels.size(); ++c) {
    const std::vector<float>& plane = image.channels[c].floats;
    for (size_t p = 0; p < pixels; ++p) result.pixels[p * result.channels + c] = plane[p];
  }
  return result;
}

}  // namespace gridrt
