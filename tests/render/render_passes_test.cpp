// A frame larger than RenderSettings::max_pass_rays is rendered in passes of whole rows
// (and adaptive supersampling's extra samples in passes of whole pixels). A pixel lies in
// one pass, so the image, its alpha and the AOVs must equal the one-pass render bit for bit.
#include <gtest/gtest.h>

#include <memory>
#include <string>

#include "cl_runtime.h"
#include "default_scene_fixture.h"
#include "gridrt_intersector.h"
#include "prepared_triangles.h"
#include "renderer.h"
#include "uniform_grid.h"

namespace gridrt {
namespace {

class RenderPasses : public test::DefaultSceneTest {
 protected:
  void SetUp() override {
    DefaultSceneTest::SetUp();
    if (IsSkipped()) return;
    grid_ = buildUniformGrid(triangles_, sceneBounds(scene_), GridSettings{});
  }
  // The frame, and how many progress scales its calls climbed, each from its start to its
  // end (uniform sampling: one; adaptive: the pixel centres, then the refinement); -1 if
  // a call went down within a scale or a scale stopped short of its end.
  Frame render(const RenderSettings& settings, const Camera& camera, int* scales = nullptr) {
    GridRtIntersector gridrt(*runtime_, grid_, PeInterrupt::Off);
    Renderer renderer(scene_, camera, gridrt, settings);
    Frame frame;
    int last = 0, last_total = 0, climbed = 0;
    bool broken = false;
    renderer.render(frame, [&](int done, int total) {
      if (last == last_total) {  // a new scale starts
        ++climbed;
        last = 0;
      } else if (total != last_total) {
        broken = true;
      }
      broken = broken || done <= last || done > total;
      last = done;
      last_total = total;
    });
    if (scales) *scales = broken || last != last_total ? -1 : climbed;
    return frame;
  }
  template <typename T>
  static size_t differing(const std::vector<T>& a, const std::vector<T>& b) {
    if (a.size() != b.size()) return std::max(a.size(), b.size());
    size_t n = 0;
    for (size_t k = 0; k < a.size(); ++k) n += a[k] != b[k] && !(a[k] != a[k] && b[k] != b[k]);
    return n;
  }
  void expectSameFrame(const Frame& want, const Frame& got, const std::string& what) {
    EXPECT_EQ(differing(want.film.rgb, got.film.rgb), 0u) << what << ": image";
    EXPECT_EQ(differing(want.film.alpha, got.film.alpha), 0u) << what << ": alpha";
    EXPECT_EQ(want.film.alpha.size(), size_t(want.film.width) * want.film.height) << what;
    EXPECT_EQ(differing(want.aovs.depth, got.aovs.depth), 0u) << what << ": depth";
    EXPECT_EQ(differing(want.aovs.primid, got.aovs.primid), 0u) << what << ": primid";
    EXPECT_EQ(differing(want.aovs.normal, got.aovs.normal), 0u) << what << ": normal";
    EXPECT_EQ(differing(want.aovs.shading_normal, got.aovs.shading_normal), 0u)
        << what << ": shading normal";
    EXPECT_EQ(differing(want.aovs.albedo, got.aovs.albedo), 0u) << what << ": albedo";
    EXPECT_EQ(differing(want.aovs.tests, got.aovs.tests), 0u) << what << ": tests";
    EXPECT_EQ(differing(want.aovs.pe, got.aovs.pe), 0u) << what << ": pe";
    EXPECT_EQ(differing(want.aovs.list_length, got.aovs.list_length), 0u) << what << ": listlen";
    EXPECT_EQ(want.rays.total(), got.rays.total()) << what;
    EXPECT_EQ(want.refined_pixels, got.refined_pixels) << what;
  }
  UniformGrid grid_;
};

RenderSettings small() {
  RenderSettings s;
  s.width = 150;
  s.height = 97;  // not a multiple of the bands' heights: a shorter last band
  s.want_aovs = true;
  s.want_diagnostics = true;
  s.want_alpha = true;
  return s;
}

TEST_F(RenderPasses, RowBandsEqualOnePass) {
  Camera orthographic = scene_.camera;
  orthographic.orthographic = true;
  orthographic.ymag = 1.2f;
  orthographic.xmag = 1.2f * 150.0f / 97.0f;
  struct Case {
    std::string name;
    RenderSettings settings;
    Camera camera;
  };
  std::vector<Case> cases;
  cases.push_back({"pinhole", small(), scene_.camera});
  RenderSettings crop = small();
  crop.crop = PixelWindow{7, 5, 141, 90};
  cases.push_back({"crop", crop, scene_.camera});
  RenderSettings jittered = small();
  jittered.spp = 3;
  cases.push_back({"spp 3", jittered, scene_.camera});
  cases.push_back({"orthographic", small(), orthographic});
  RenderSettings adaptive = small();
  adaptive.adaptive_aa = true;
  adaptive.aa_samples = 4;
  cases.push_back({"adaptive", adaptive, scene_.camera});
  for (const Case& c : cases) {
    RenderSettings one = c.settings;
    one.max_pass_rays = size_t(1) << 30;
    const Frame want = render(one, c.camera);
    RenderSettings many = c.settings;
    many.max_pass_rays = 2000;
    int scales = 0;
    const Frame got = render(many, c.camera, &scales);
    // ceil(rows / floor(2000 / samples per row)) bands: 97 rows of 150 samples in 8 bands,
    // the crop's 85 rows of 134 in 7, 97 rows of 450 in 25; the refinement in passes of
    // 500 pixels of 4 samples.
    const uint64_t bands = c.settings.spp == 3 ? 25 : c.name == "crop" ? 7 : 8;
    EXPECT_EQ(want.passes, c.settings.adaptive_aa ? 2u : 1u) << c.name;
    if (c.settings.adaptive_aa)
      EXPECT_EQ(got.passes, bands + (got.refined_pixels + 499) / 500) << c.name;
    else
      EXPECT_EQ(got.passes, bands) << c.name;
    EXPECT_EQ(scales, c.settings.adaptive_aa ? 2 : 1) << c.name << ": progress";
    expectSameFrame(want, got, c.name);
  }
}

// A row is never split: a budget smaller than one row's samples renders row by row.
TEST_F(RenderPasses, ABudgetBelowOneRowRendersRowByRow) {
  RenderSettings one = small();
  one.spp = 2;
  const Frame want = render(one, scene_.camera);
  RenderSettings rows = one;
  rows.max_pass_rays = 1;
  const Frame got = render(rows, scene_.camera);
  EXPECT_EQ(got.passes, uint64_t(one.height));
  expectSameFrame(want, got, "one row per pass");
}

// One renderer, several frames (gridrt --repeat): what it keeps between frames (the
// band's pixel list, headlight radiance added straight to the pixels) must not leak into
// the next frame. Adaptive sampling replaces the pixel list with its refined pixels.
TEST_F(RenderPasses, RepeatedFramesOfOneRendererAreEqual) {
  for (const bool primary_only : {false, true}) {
    RenderSettings s = small();
    s.adaptive_aa = true;
    s.aa_samples = 2;
    s.primary_only = primary_only;
    GridRtIntersector gridrt(*runtime_, grid_, PeInterrupt::Off);
    Renderer renderer(scene_, scene_.camera, gridrt, s);
    Frame first, second, third;
    renderer.render(first);
    renderer.render(second);
    EXPECT_GT(first.refined_pixels, 0u);
    expectSameFrame(first, second, primary_only ? "headlight, again" : "Whitted, again");
    RenderSettings uniform = s;
    uniform.adaptive_aa = false;
    Renderer plain(scene_, scene_.camera, gridrt, uniform);
    plain.render(first);
    plain.render(third);
    expectSameFrame(first, third,
                    primary_only ? "headlight, uniform again" : "Whitted, uniform again");
  }
}

// One renderer whose bands change from frame to frame: a frame of one jittered sample a
// pixel (the viewer's progressive frames) cuts the rows into other bands than a frame of
// all three samples. Each band's pixel list is kept between frames, so it must be made
// again when its band changes; the frames go into one Frame, whose film buffer the
// renderer takes back for the next frame's radiance.
TEST_F(RenderPasses, BandsThatChangeBetweenFramesGiveTheirOwnPixels) {
  RenderSettings s = small();
  s.spp = 3;
  s.max_pass_rays = 2000;
  GridRtIntersector gridrt(*runtime_, grid_, PeInterrupt::Off);
  Renderer fresh_all(scene_, scene_.camera, gridrt, s);
  Frame all_samples;
  fresh_all.render(all_samples);
  RenderSettings one_sample = s;
  one_sample.single_sample = 1;
  Renderer fresh_one(scene_, scene_.camera, gridrt, one_sample);
  Frame sample_one;
  fresh_one.render(sample_one);
  EXPECT_EQ(all_samples.passes, 25u);  // 97 rows of 450 samples
  EXPECT_EQ(sample_one.passes, 8u);    // 97 rows of 150

  Renderer renderer(scene_, scene_.camera, gridrt, s);
  Frame frame;
  for (const int sample : {-1, 1, -1, 1}) {
    renderer.setSingleSample(sample);
    renderer.render(frame);
    expectSameFrame(sample < 0 ? all_samples : sample_one, frame,
                    sample < 0 ? "all samples after one" : "one sample after all");
  }
}

}  // namespace
}  // namespace gridrt
