// What the window shows: the image, or one of the primary rays' AOVs as a picture, with
// the false colours of tools/heatmap.py (a hashed colour per PE; viridis for counts, 0 ..
// the picture's largest value), depth in viridis from the nearest hit to the farthest.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "film.h"
#include "renderer.h"

namespace gridrt {

enum class ViewKind { Image, Depth, Normal, Albedo, Pe, Tests, ListLength };
constexpr int kViewKinds = 7;

// "image", "depth", "normal", "albedo", "pe", "tests", "listlen" (the --aov names).
const char* viewName(ViewKind kind);
// The view after `kind`, the last followed by the first.
ViewKind nextView(ViewKind kind);
// Which of the renderer's outputs the view needs (RenderSettings::want_aovs,
// want_diagnostics).
bool needsAovs(ViewKind kind);
bool needsDiagnostics(ViewKind kind);

// 8-bit RGB codes, row 0 at the top.
struct Picture {
  int width = 0, height = 0;
  std::vector<unsigned char> rgb;  // width * height * 3
};

// The film's colour as the PNG holds it (image_output.h: the same 8-bit codes).
Picture imagePicture(const Film& film);
// View `kind` (not Image) of the AOVs of a width x height frame.
Picture aovPicture(ViewKind kind, const PrimaryAovs& aovs, int width, int height);

// tools/heatmap.py's colour of PE `id`: a PCG-style hash of the id mapped to a bright hue;
// black for a miss (negative id).
void peColour(int32_t id, unsigned char rgb[3]);
// viridis at v in [0, 1] (clamped), linear between its colours at 0, 1/4, 1/2, 3/4 and 1.
void viridisColour(float v, unsigned char rgb[3]);

}  // namespace gridrt
