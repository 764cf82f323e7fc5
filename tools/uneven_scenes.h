// The uneven scenes around a dense model (tools/make_uneven_scenes writes them as files; the
// adaptive grid's tests and tools/bench.py's adaptive set use them): the model on square
// floors 1 to 1000 times its size, copies scattered far apart, a row of copies, and one huge
// triangle through the model. Each has a point light and a camera (yfov 40 degrees, 4:3).
// Deterministic: the same triangles in the same order on every call. The model's size is
// the largest extent of its bounding box.
#pragma once
#include <string>
#include <utility>
#include <vector>

#include "scene.h"

namespace gridrt {

// The model on a square floor `scale` times its size at its lowest point, centred below it;
// the camera 1.6 sizes from the model's centre, a little above it, looking at it.
Scene floorScene(const Scene& model, float scale);
// Eight copies at the corners of a cube `spread` times the model's size; the camera beside
// the first, looking past it towards the cube's centre.
Scene scatteredScene(const Scene& model, float spread);
// `count` copies in a row along +X, 1.5 sizes apart; the camera at the row's start, off to
// the side, looking along it.
Scene rowScene(const Scene& model, int count);
// The model and one triangle `scale` times its size through its centre, tilted.
Scene hugeTriangleScene(const Scene& model, float scale);

// The family by file name (without .glb): floor_1x, floor_10x, floor_100x, floor_1000x,
// scattered (spread 60), row (`row_count` copies), huge_triangle (scale 100).
std::vector<std::pair<std::string, Scene>> unevenScenes(const Scene& model, int row_count = 16);

}  // namespace gridrt
