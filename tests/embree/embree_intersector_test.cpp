// The Embree peer's intersector (tools/embree_intersector.h), built where Embree is
// installed (tools/setup.sh --bench): the benchmarks compare gridrt with it, so it must
// trace the rays gridrt's renderer hands it as the exact reference does. Each test fails
// if a ray field is dropped on the way into Embree (tmin, tmax), if the packets' lanes and
// the rays do not line up, or if the occlusion query's answer is read the wrong way round.
#include "embree_intersector.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "camera_rays.h"
#include "default_scene.h"
#include "gltf_loader.h"
#include "pinhole_view.h"
#include "prepared_triangles.h"
#include "reference_intersector.h"
#include "renderer.h"
#include "test_support.h"

namespace gridrt {
namespace {

constexpr int kWidth = 160, kHeight = 120;
// Embree keeps another triangle than the lowest-index rule where two lie at equal or
// near-equal distance (neighbouring faces, bunny_res4's duplicates): a different triangle
// within this relative distance of the reference's hit is a tie, not a disagreement.
constexpr float kTieRelative = 1e-5f;
// A Whitted pixel differs when a channel is further than this (linear) from the
// reference's; at most kDifferingPixelShare of the pixels may (seam near ties).
constexpr float kPixelTolerance = 0.01f;
constexpr double kDifferingPixelShare = 0.005;

struct CameraRays {
  Camera camera;
  PixelWindow image{0, 0, kWidth, kHeight};
  std::vector<GrRay> rays;
};

CameraRays cameraRaysOf(const Scene& scene) {
  CameraRays c;
  c.camera = scene.has_camera ? scene.camera : defaultCamera(sceneBounds(scene));
  c.rays.resize(size_t(kWidth) * kHeight);
  CameraRayGenerator(c.camera, kWidth, kHeight).centreWindow(c.image, c.rays.data());
  return c;
}

// Rays whose hit disagrees with the reference's beyond a tie: a hit against a miss, or
// another triangle at a distance more than `relative` of the reference's away.
size_t disagreements(const std::vector<GrHit>& want, const std::vector<GrHit>& got,
                     float relative) {
  size_t bad = 0;
  for (size_t i = 0; i < want.size(); ++i) {
    if ((want[i].prim >= 0) != (got[i].prim >= 0))
      ++bad;
    else if (want[i].prim >= 0 && want[i].prim != got[i].prim &&
             std::fabs(got[i].t - want[i].t) > relative * want[i].t)
      ++bad;
  }
  return bad;
}

TEST(EmbreeIntersector, CameraRaysFindTheReferenceTriangles) {
  const Scene scene = loadGltfFile(test::modelScene("bunny_res4.glb"));
  const CameraRays c = cameraRaysOf(scene);
  ReferenceIntersector reference(scene);
  std::vector<GrHit> want;
  reference.intersect(c.rays, HitMode::Closest, want, nullptr);
  size_t hits = 0;
  for (const GrHit& h : want) hits += h.prim >= 0;
  ASSERT_GT(hits, want.size() / 5);  // the bunny fills the view

  const PinholeView view = PinholeView::of(c.camera, kWidth, kHeight, c.image);
  for (int packet : {1, 8, 16}) {
    EmbreeIntersector embree(scene, 2, packet);
    std::vector<GrHit> tiles, runs;
    embree.intersectPrimary(view, c.rays, tiles, nullptr);
    embree.intersect(c.rays, HitMode::Closest, runs, nullptr);
    EXPECT_EQ(disagreements(want, tiles, kTieRelative), 0u) << embree.name() << ", camera tiles";
    EXPECT_EQ(disagreements(want, runs, kTieRelative), 0u) << embree.name() << ", runs of rays";
  }
}

TEST(EmbreeIntersector, OcclusionRespectsTheRaysInterval) {
  const Scene scene = loadGltfFile(test::modelScene("bunny_res4.glb"));
  CameraRays c = cameraRaysOf(scene);
  ReferenceIntersector reference(scene);
  std::vector<GrHit> want;
  reference.intersect(c.rays, HitMode::Closest, want, nullptr);
  for (int packet : {1, 16}) {
    EmbreeIntersector embree(scene, 2, packet);
    std::vector<GrHit> open, short_of_it, past_it;
    embree.intersect(c.rays, HitMode::AnyHit, open, nullptr);
    EXPECT_EQ(disagreements(want, open, INFINITY), 0u) << embree.name() << ", [0, inf)";
    // Each hitting ray cut to half its hit distance: nothing lies before its first hit.
    std::vector<GrRay> cut = c.rays, late = c.rays;
    size_t cut_rays = 0;
    for (size_t i = 0; i < cut.size(); ++i)
      if (want[i].prim >= 0) {
        cut[i].tmax = 0.5f * want[i].t;
        late[i].tmin = 1e3f;  // and starting past the whole bunny (it lies within 1 of the eye)
        ++cut_rays;
      }
    embree.intersect(cut, HitMode::AnyHit, short_of_it, nullptr);
    embree.intersect(late, HitMode::AnyHit, past_it, nullptr);
    size_t occluded_short = 0, occluded_late = 0;
    for (size_t i = 0; i < cut.size(); ++i) {
      occluded_short += short_of_it[i].prim >= 0;
      occluded_late += past_it[i].prim >= 0;
    }
    EXPECT_GT(cut_rays, 0u);
    EXPECT_EQ(occluded_short, 0u) << embree.name() << ": tmax ignored";
    EXPECT_EQ(occluded_late, 0u) << embree.name() << ": tmin ignored";
  }
}

// The frame the Whitted benchmark times: gridrt's renderer with Embree tracing must render
// what it renders with the exact reference, up to near ties along the room's seams.
TEST(EmbreeIntersector, WhittedFrameMatchesTheReferenceRenderer) {
  const Scene scene = makeDefaultScene();
  RenderSettings settings;
  settings.width = kWidth;
  settings.height = kHeight;
  ReferenceIntersector reference(scene);
  Frame want;
  Renderer(scene, scene.camera, reference, settings).render(want);
  ASSERT_GT(want.rays.shadow, 0u);
  ASSERT_GT(want.rays.reflection + want.rays.refraction, 0u);
  for (int packet : {1, 16}) {
    EmbreeIntersector embree(scene, 2, packet);
    Frame got;
    Renderer(scene, scene.camera, embree, settings).render(got);
    EXPECT_EQ(got.rays.primary, want.rays.primary) << embree.name();
    EXPECT_EQ(got.rays.shadow, want.rays.shadow) << embree.name();
    EXPECT_EQ(got.rays.reflection, want.rays.reflection) << embree.name();
    EXPECT_EQ(got.rays.refraction, want.rays.refraction) << embree.name();
    size_t differ = 0;
    for (size_t p = 0; p < want.film.rgb.size() / 3; ++p)
      for (int k = 0; k < 3; ++k)
        if (std::fabs(got.film.rgb[3 * p + k] - want.film.rgb[3 * p + k]) > kPixelTolerance) {
          ++differ;
          break;
        }
    EXPECT_LE(double(differ), kDifferingPixelShare * double(want.film.rgb.size() / 3))
        << embree.name() << ": too many pixels off the reference";
  }
}

}  // namespace
}  // namespace gridrt
