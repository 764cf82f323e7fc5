// The vectorised row generator must give the very rays of the per-pixel generator: the
// renderer uses the first, every reference and test the second.
#include "camera_rays.h"

#include <gtest/gtest.h>

#include <vector>

#include "test_support.h"

namespace gridrt {
namespace {

using test::sameBits;  // a ray compared field by field, as bits

TEST(CameraRays, CentreRowEqualsPerPixelRaysBitForBit) {
  struct Case {
    glm::vec3 eye, target;
    float yfov;
    int width, height;
  };
  const Case cases[] = {{{0, 1, 4}, {0, 1, 0}, 0.8f, 97, 61},
                        {{3.5f, -2, 1e3f}, {-1, 7, 2}, 0.1f, 130, 7},
                        {{1e-3f, 2e-3f, 0}, {5, 5, 5}, 2.5f, 64, 64}};
  for (const Case& c : cases) {
    Camera camera = lookAtCamera(c.eye, c.target, c.yfov);
    CameraRayGenerator generate(camera, c.width, c.height);
    std::vector<GrRay> row(c.width);
    int differing = 0;
    for (int j = 0; j < c.height; ++j) {
      generate.centreRow(j, 3, c.width, row.data());
      for (int i = 3; i < c.width; ++i)
        differing += !sameBits(row[i - 3], generate(i, j, 0.5f, 0.5f));
    }
    EXPECT_EQ(differing, 0) << c.width << "x" << c.height;
  }
}

TEST(CameraRays, CentreRowOfAnOrthographicCameraEqualsPerPixelRays) {
  Camera camera = lookAtCamera({0, 0, 5}, {0, 0, 0}, 1.0f);
  camera.orthographic = true;
  camera.ymag = 2.0f;
  CameraRayGenerator generate(camera, 40, 30);
  std::vector<GrRay> row(40);
  generate.centreRow(7, 0, 40, row.data());
  for (int i = 0; i < 40; ++i) EXPECT_TRUE(sameBits(row[i], generate(i, 7, 0.5f, 0.5f))) << i;
}

// The grid's margin scales with where rays start (GridSettings::ray_origins): the box
// must hold every primary ray's origin, jittered samples included, for a pinhole camera
// (its eye) and an orthographic one (its whole image rectangle).
TEST(CameraRays, PrimaryRayOriginsHoldEveryRaysOrigin) {
  Camera pinhole = lookAtCamera({1e3f, -20, 7}, {0, 0, 0}, 0.7f);
  Camera ortho = lookAtCamera({3, 4, 50}, {0, 1, 0}, 1.0f);
  ortho.orthographic = true;
  ortho.ymag = 6.0f;
  for (const Camera* camera : {&pinhole, &ortho}) {
    const int w = 37, h = 23;
    const Bounds box = primaryRayOrigins(*camera, w, h);
    const CameraRayGenerator generate(*camera, w, h);
    int outside = 0;
    for (int j = 0; j < h; ++j)
      for (int i = 0; i < w; ++i)
        for (uint32_t s = 0; s < 4; ++s) {
          float sx, sy;
          jitter(uint32_t(j * w + i), s, sx, sy);
          const GrRay r = generate(i, j, sx, sy);
          outside += !(r.ox >= box.lo.x && r.ox <= box.hi.x && r.oy >= box.lo.y &&
                       r.oy <= box.hi.y && r.oz >= box.lo.z && r.oz <= box.hi.z);
        }
    EXPECT_EQ(outside, 0) << (camera->orthographic ? "orthographic" : "pinhole");
  }
}

}  // namespace
}  // namespace gridrt
