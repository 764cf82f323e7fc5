// gridrt.render: one still frame in memory, as the command line renders it for -o: the
// options parsed by its parser (python_options.h), the scene loaded and framed as it loads
// and frames it (host/app/scene_source.h), and the frame job's render it runs
// (host/app/frame_render.h: PreparedScene, then the Renderer's frame loop).
#pragma once
#include <string>
#include <vector>

#include "scene.h"

namespace gridrt {

// The -o image's pixels: height x width x channels floats (R, G, B, with --alpha A),
// linear, row 0 at the top, what an .exr of the same options holds.
struct RenderedImage {
  int width = 0, height = 0, channels = 0;
  std::vector<float> pixels;
  std::vector<std::string> warnings;  // what the command line would print as warnings
};

// arguments: the command line without the program's name. scene: a scene to render
// instead of the arguments' SCENE (null: the arguments' SCENE, or the default scene).
RenderedImage renderImage(const std::vector<std::string>& arguments, const Scene* scene);

}  // namespace gridrt
