// The scene `gridrt -` reads: a glTF document (JSON, or GLB by its "glTF" magic) from
// standard input, read whole into memory once (an animation poses the document it holds,
// frame after frame), its external files looked up in the current directory.
#pragma once
#include "gltf_loader.h"

namespace gridrt {

// Throws SceneError with one line when standard input is a terminal, cannot be read, is
// empty or holds no valid glTF ("standard input: ...").
GltfDocument readStandardInputScene();

}  // namespace gridrt
