#include "view_pictures.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "eight_bit_image.h"
#include "image_output.h"
#include "parallel_loops.h"

namespace gridrt {

namespace {

struct ViewInfo {
  ViewKind kind;
  const char* name;
  bool aovs, diagnostics;
};
constexpr ViewInfo kViews[kViewKinds] = {
    {ViewKind::Image, "image", false, false},     {ViewKind::Depth, "depth", true, false},
    {ViewKind::Normal, "normal", true, false},    {ViewKind::Albedo, "albedo", true, false},
    {ViewKind::Pe, "pe", false, true},            {ViewKind::Tests, "tests", false, true},
    {ViewKind::ListLength, "listlen", false, true}};

const ViewInfo& infoOf(ViewKind kind) { return kViews[int(kind)]; }

// viridis's colours at 0, 1/4, 1/2, 3/4, 1 (#440154, #3b528b, #21918c, #5ec962, #fde725).
constexpr unsigned char kViridisStops[5][3] = {
    {68, 1, 84}, {59, 82, 139}, {33, 145, 140}, {94, 201, 98}, {253, 231, 37}};

unsigned char code(float v) { return (unsigned char)(std::clamp(v, 0.0f, 1.0f) * 255.0f + 0.5f); }

// Each pixel's value (misses as `miss`), its colour by viridis from 0 to the largest value
// (at least `least_max`), misses black.
template <typename Value>
Picture viridisPicture(const std::vector<Value>& values, int width, int height, float least_max,
                       bool (*is_miss)(Value)) {
  Picture p{width, height, std::vector<unsigned char>(size_t(width) * height * 3, 0)};
  float top = least_max;
  for (size_t k = 0; k < values.size(); ++k)
    if (!is_miss(values[k])) top = std::max(top, float(values[k]));
  parallelFor(size_t(0), values.size(), [&](size_t k) {
    if (!is_miss(values[k])) viridisColour(float(values[k]) / top, &p.rgb[3 * k]);
  });
  return p;
}

}  // namespace

const char* viewName(ViewKind kind) { return infoOf(kind).name; }
ViewKind nextView(ViewKind kind) { return ViewKind((int(kind) + 1) % kViewKinds); }
bool needsAovs(ViewKind kind) { return infoOf(kind).aovs; }
bool needsDiagnostics(ViewKind kind) { return infoOf(kind).diagnostics; }

void viridisColour(float v, unsigned char rgb[3]) {
  const float x = std::clamp(std::isnan(v) ? 0.0f : v, 0.0f, 1.0f) * 4.0f;
  const int i = std::min(3, int(x));
  const float f = x - float(i);
  for (int c = 0; c < 3; ++c)
    rgb[c] = (unsigned char)(std::lround(float(kViridisStops[i][c]) * (1.0f - f) +
                                         float(kViridisStops[i + 1][c]) * f));
}

void peColour(int32_t id, unsigned char rgb[3]) {
  if (id < 0) {
    rgb[0] = rgb[1] = rgb[2] = 0;
    return;
  }
  // tools/heatmap.py's hashed_colours, in 32-bit unsigned arithmetic as numpy's uint32.
  uint32_t v = uint32_t(id);
  v = v * 747796405u + 2891336453u;
  v = ((v >> ((v >> 28u) + 4u)) ^ v) * 277803737u;
  v = (v >> 22u) ^ v;
  const double hue = double(v & 0xFFFFu) / 65536.0;
  const double sat = 0.55 + 0.45 * double((v >> 16u) & 0xFFu) / 255.0;
  const double val = 0.70 + 0.30 * double((v >> 24u) & 0xFFu) / 255.0;
  // HSV to RGB as matplotlib.colors.hsv_to_rgb.
  const int sector = int(hue * 6.0) % 6;
  const double f = hue * 6.0 - std::floor(hue * 6.0);
  const double p = val * (1.0 - sat), q = val * (1.0 - sat * f), t = val * (1.0 - sat * (1.0 - f));
  const double table[6][3] = {{val, t, p}, {q, val, p}, {p, val, t},
                              {p, q, val}, {t, p, val}, {val, p, q}};
  for (int c = 0; c < 3; ++c) rgb[c] = (unsigned char)(table[sector][c] * 255.0 + 0.5);
}

Picture imagePicture(const Film& film) {
  LayeredImage image = filmImage(film);
  // The window shows the colour; an alpha channel stays in the file.
  image.channels.resize(3);
  EightBitImage codes = eightBitImage(image, "png");
  return Picture{film.width, film.height, std::move(codes.codes)};
}

Picture aovPicture(ViewKind kind, const PrimaryAovs& aovs, int width, int height) {
  const size_t pixels = size_t(width) * height;
  Picture p{width, height, std::vector<unsigned char>(pixels * 3, 0)};
  switch (kind) {
    case ViewKind::Depth: {
      // From the nearest hit (purple) to the farthest (yellow); misses black.
      float nearest = std::numeric_limits<float>::infinity(), farthest = 0.0f;
      for (float d : aovs.depth)
        if (d >= 0.0f) nearest = std::min(nearest, d), farthest = std::max(farthest, d);
      const float range = farthest > nearest ? farthest - nearest : 1.0f;
      parallelFor(size_t(0), std::min(pixels, aovs.depth.size()), [&](size_t k) {
        if (aovs.depth[k] >= 0.0f) viridisColour((aovs.depth[k] - nearest) / range, &p.rgb[3 * k]);
      });
      return p;
    }
    case ViewKind::Tests:
      return viridisPicture<float>(aovs.tests, width, height, 1.0f, [](float) { return false; });
    case ViewKind::ListLength:
      return viridisPicture<float>(aovs.list_length, width, height, 1.0f,
                                   [](float) { return false; });
    case ViewKind::Pe:
      parallelFor(size_t(0), std::min(pixels, aovs.pe.size()),
                  [&](size_t k) { peColour(aovs.pe[k], &p.rgb[3 * k]); });
      return p;
    case ViewKind::Normal:
      // Each component from [-1, 1] to [0, 1]; a miss (0, 0, 0) black.
      parallelFor(size_t(0), std::min(pixels, aovs.shading_normal.size() / 3), [&](size_t k) {
        const float* n = &aovs.shading_normal[3 * k];
        if (n[0] == 0.0f && n[1] == 0.0f && n[2] == 0.0f) return;
        for (int c = 0; c < 3; ++c) p.rgb[3 * k + c] = code(0.5f * n[c] + 0.5f);
      });
      return p;
    case ViewKind::Albedo:
      parallelFor(size_t(0), std::min(pixels, aovs.albedo.size() / 3), [&](size_t k) {
        for (int c = 0; c < 3; ++c) p.rgb[3 * k + c] = linearToSrgb8(std::clamp(aovs.albedo[3 * k + c], 0.0f, 1.0f));
      });
      return p;
    case ViewKind::Image:
      break;
  }
  return p;
}

}  // namespace gridrt
