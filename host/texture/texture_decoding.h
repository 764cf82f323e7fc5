// The step between loading a scene and rendering it: its images decoded into texels
// (Scene::images[i].colour and .data), which the scene library cannot do itself since it
// links no image decoder (only host/image links OpenImageIO). Without it a scene renders
// with its materials' factors alone.
#pragma once
#include "scene.h"

namespace gridrt {

// Decodes every image a material reads, once per use: for base colour and emissive
// textures into `colour` (the sRGB transfer undone on RGB, alpha as stored), for
// metallic-roughness, occlusion and normal textures into `data` (as stored); grey images are spread
// to RGB, a missing alpha is 1; each with its mip levels (mip_levels.h). An image that cannot be
// decoded (no bytes, an unknown format, corrupt, too large) is left empty and named in one warning
// in Scene::warnings: its textures then look up nothing.
void decodeTextures(Scene& scene);

}  // namespace gridrt
