// Lights for a scene that has none, as glTF viewers light a bare model: a directional key
// light from above and to the left of the camera and a dimmer fill from its right, both
// from the camera's side. Directional, so that the exposure does not depend on the scene's
// size or on how near a surface is: a white Lambert surface facing the key renders at
// kKeyExposure, one facing the fill at kFillExposure; shape is read from the shading, and
// nothing washes out to white.
#pragma once
#include <vector>

#include "scene.h"

namespace gridrt {

constexpr float kKeyExposure = 0.8f;   // a white surface facing the key light
constexpr float kFillExposure = 0.3f;  // a white surface facing the fill light

// Two directional lights, placed relative to `camera` (its world matrix: +X right, +Y up,
// looking down -Z).
std::vector<Light> defaultLights(const Camera& camera);

}  // namespace gridrt
