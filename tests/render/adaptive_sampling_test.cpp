// "Model no more than a scene needs": adaptive supersampling and adaptive depth trace
// fewer rays than their uniform twins, at a bounded cost in error.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>

#include "brute_intersector.h"
#include "cl_runtime.h"
#include "default_scene_fixture.h"
#include "prepared_triangles.h"
#include "renderer.h"

namespace gridrt {
namespace {

class Adaptive : public test::DefaultSceneTest {
 protected:
  Frame render(RenderSettings settings) {
    BruteIntersector brute(*runtime_, triangles_);
    Renderer renderer(scene_, scene_.camera, brute, settings);
    Frame frame;
    renderer.render(frame);
    return frame;
  }
  // Error of the displayed image: both clamped to [0, 1] as a PNG would show them.
  static double rmse(const Film& a, const Film& b) {
    double sum = 0;
    for (size_t k = 0; k < a.rgb.size(); ++k) {
      double d = std::clamp(a.rgb[k], 0.0f, 1.0f) - std::clamp(b.rgb[k], 0.0f, 1.0f);
      sum += d * d;
    }
    return std::sqrt(sum / double(a.rgb.size()));
  }
  static RenderSettings small() {
    RenderSettings s;
    s.width = 128;
    s.height = 96;
    return s;
  }
};

TEST_F(Adaptive, SupersamplingRefinesOnlyEdgesAndBeatsOneSampleForFewerRaysThanUniform) {
  RenderSettings reference = small();
  reference.spp = 32;
  Frame truth = render(reference);
  RenderSettings one = small();
  Frame single = render(one);
  RenderSettings uniform = small();
  uniform.spp = 9;
  Frame nine = render(uniform);
  RenderSettings adaptive = small();
  adaptive.adaptive_aa = true;
  adaptive.aa_samples = 8;
  Frame adapt = render(adaptive);
  const size_t pixels = 128 * 96;
  EXPECT_GT(adapt.refined_pixels, 0u);
  EXPECT_LT(adapt.refined_pixels, pixels / 2) << "refinement should stay near edges";
  EXPECT_LT(adapt.rays.primary, nine.rays.primary / 2);
  double e1 = rmse(single.film, truth.film), ea = rmse(adapt.film, truth.film),
         e9 = rmse(nine.film, truth.film);
  std::printf("rmse vs 32 spp: 1 spp %.5f, adaptive %.5f (%llu primary rays), 9 spp %.5f (%llu)\n",
              e1, ea, (unsigned long long)adapt.rays.primary, e9,
              (unsigned long long)nine.rays.primary);
  EXPECT_LT(ea, 0.5 * e1);   // far better than one sample
  EXPECT_LT(ea, 1.25 * e9);  // close to uniform 9 spp at a fraction of the rays
}

// The refined pixels are exactly those whose centre differs from the centre of one of its
// four neighbours (left, right, above, below) by more than the threshold in some channel,
// found here from a plain one-sample render; every other pixel keeps its centre's value bit
// for bit. Both kinds of neighbour matter: the default scene's horizontal edges (floor,
// ceiling, the block's top) refine pixels that only a vertical neighbour tells apart.
TEST_F(Adaptive, RefinesExactlyThePixelsWhoseCentreDiffersFromAFourNeighbour) {
  const int w = 128, h = 96;
  Frame centres = render(small());
  RenderSettings adaptive = small();
  adaptive.adaptive_aa = true;
  adaptive.aa_samples = 4;
  Frame adapt = render(adaptive);
  const std::vector<float>& c = centres.film.rgb;
  auto differs = [&](int p, int q) {
    for (int k = 0; k < 3; ++k)
      if (std::fabs(c[3 * p + k] - c[3 * q + k]) > adaptive.aa_threshold) return true;
    return false;
  };
  size_t want = 0, only_vertical = 0, kept = 0, unrefined = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const int p = y * w + x;
      const bool horizontal = (x > 0 && differs(p, p - 1)) || (x + 1 < w && differs(p, p + 1));
      const bool vertical = (y > 0 && differs(p, p - w)) || (y + 1 < h && differs(p, p + w));
      want += horizontal || vertical;
      only_vertical += vertical && !horizontal;
      if (horizontal || vertical) continue;
      ++unrefined;
      bool same = true;
      for (int k = 0; k < 3; ++k) same &= adapt.film.rgb[3 * p + k] == c[3 * p + k];
      kept += same;
    }
  ASSERT_GT(only_vertical, 0u) << "the scene no longer has pixels refined for a vertical edge";
  EXPECT_EQ(adapt.refined_pixels, want);
  EXPECT_EQ(kept, unrefined) << "a pixel with no differing neighbour was refined";
  EXPECT_EQ(adapt.rays.primary, uint64_t(w) * h + want * 4);
}

TEST_F(Adaptive, DepthCutoffTracesFewerRaysWithinABoundedError) {
  RenderSettings full = small();
  Frame all = render(full);
  RenderSettings cut = small();
  cut.min_path_weight = 0.05f;
  Frame fewer = render(cut);
  uint64_t secondary_all = all.rays.reflection + all.rays.refraction;
  uint64_t secondary_cut = fewer.rays.reflection + fewer.rays.refraction;
  EXPECT_LT(secondary_cut, secondary_all);
  double e = rmse(all.film, fewer.film);
  std::printf("secondary rays %llu -> %llu, rmse %.5f\n", (unsigned long long)secondary_all,
              (unsigned long long)secondary_cut, e);
  EXPECT_GT(e, 0.0);   // something was really left out
  EXPECT_LT(e, 0.02);  // paths below 5 % throughput carry little light
}

}  // namespace
}  // namespace gridrt
