// Progressive refinement: the frames of one sample each (RenderSettings::single_sample)
// are the --spp frame's samples, so their mean is the --spp image up to the order of the
// sums; one sample a pixel is the command line's frame bit for bit.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "camera_rays.h"
#include "default_scene_fixture.h"
#include "gridrt_intersector.h"
#include "progressive_film.h"
#include "renderer.h"
#include "adaptive_grid.h"
#include "uniform_grid.h"

namespace gridrt {
namespace {

// The mean of n floats summed in double and divided once, against the renderer's sum of
// x / n in float: a few float ulps (2^-23 each) relative to the value, or to 1 below it.
constexpr float kSumOrderTolerance = 1e-6f;

class ProgressiveRefinement : public test::DefaultSceneTest {
 protected:
  Frame render(int spp, int single_sample) {
    GridSettings grid;
    grid.ray_origins = primaryRayOrigins(scene_.camera, kWidth, kHeight);
    const UniformGrid g = buildGrid(triangles_, sceneBounds(scene_), grid);
    GridRtIntersector intersector(*runtime_, g, PeInterrupt::CameraRays, KernelOptions{});
    RenderSettings settings;
    settings.width = kWidth, settings.height = kHeight, settings.spp = spp;
    settings.want_aovs = false;
    Renderer renderer(scene_, scene_.camera, intersector, settings);
    renderer.setSingleSample(single_sample);
    Frame frame;
    renderer.render(frame);
    return frame;
  }
  static constexpr int kWidth = 64, kHeight = 48;
};

TEST_F(ProgressiveRefinement, SingleSamplesAddUpToTheSppFrame) {
  const int spp = 4;
  const Frame whole = render(spp, -1);
  ProgressiveFilm film;
  std::vector<Frame> samples;
  for (int s = 0; s < spp; ++s) {
    samples.push_back(render(spp, s));
    film.add(samples.back().film);
  }
  EXPECT_EQ(film.samples(), spp);
  EXPECT_EQ(samples[0].rays.primary, uint64_t(kWidth) * kHeight);
  // Jittered, each sample its own: no two alike, none the pixel centres.
  const Frame centres = render(1, -1);
  EXPECT_NE(samples[0].film.rgb, centres.film.rgb);
  EXPECT_NE(samples[0].film.rgb, samples[1].film.rgb);
  const Film& mean = film.mean();
  ASSERT_EQ(mean.rgb.size(), whole.film.rgb.size());
  for (size_t k = 0; k < mean.rgb.size(); ++k)
    ASSERT_NEAR(mean.rgb[k], whole.film.rgb[k],
                kSumOrderTolerance * std::max(1.0f, std::fabs(whole.film.rgb[k])))
        << k;
}

TEST_F(ProgressiveRefinement, OneSampleIsTheFrameItself) {
  const Frame frame = render(1, -1);
  ProgressiveFilm film;
  film.add(frame.film);
  EXPECT_EQ(film.mean().rgb, frame.film.rgb);
  film.restart();
  EXPECT_EQ(film.samples(), 0);
}

}  // namespace
}  // namespace gridrt
