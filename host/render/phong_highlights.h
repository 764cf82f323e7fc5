// Phong highlights, 16 hits at a time: rv, the cosine between the light's direction
// mirrored about the shading normal and the way back along the ray (0 where negative),
// and rv^exponent, in vector lanes as exp(exponent * log(rv)) (Highway's exp and log).
// std::pow has no vector form here: one call per lit hit took ~4 % of a default Whitted
// frame's samples. One hit's highlight (phongHighlight) runs the same arithmetic in a lane,
// so both give the same bits; an exponent of 1 (a rough surface's) gives rv itself, as
// std::pow does.
#pragma once
#include "hit_surfaces.h"

namespace gridrt {

// rv^exponent lies within this share of the exact power for rv in (0, 1] and exponent in
// [1, 10000] (Phong exponents, whitted_shading.h) wherever the exact power is at least
// kHighlightFloor (7.5e-6 measured): log's error of a few ulps grows by exponent * |log(rv)|,
// at most ln(1e30) = 69 there (below, the power is too small to show).
constexpr float kHighlightRelativeError = 1e-5f;
// Below this the highlight is at most this absolute amount off (it may flush to 0 where
// std::pow gives a subnormal): a light of irradiance E adds under E * 1e-30 there.
constexpr float kHighlightFloor = 1e-30f;

// The highlights of `light` at the 16 hits of `s` (the lanes past a block's hits too),
// each with its own exponent: fills light.rv and light.highlight.
void computeHighlights(const SurfaceLanes& s, const float* exponent, LightLanes& light);

// One hit's highlight from its rv and exponent: one lane of computeHighlights.
float phongHighlight(float rv, float exponent);

}  // namespace gridrt
