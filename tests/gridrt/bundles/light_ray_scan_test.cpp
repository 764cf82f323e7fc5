// The light bundles' first pass in vector lanes (host/gridrt/bundles/light_ray_scan.h) gives
// every ray the face, face point and origin depth of the one-ray definition bit for bit, and
// the same windows and bounds, on rays towards a light from every side, along the axes and
// the cube's edges (the ties of the face choice), and without a direction or a number.
#include "light_ray_scan.h"

#include <gtest/gtest.h>

#include <limits>
#include <random>
#include <set>
#include <vector>

#include "test_support.h"

namespace gridrt {
namespace {

using test::sameBits;

// Rays towards `light` from points all around it.
std::vector<GrRay> raysTowards(const glm::vec3& light, size_t count) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  std::vector<GrRay> rays;
  for (size_t k = 0; k < count; ++k) {
    const glm::vec3 o = light + 5.0f * glm::vec3(unit(rng), unit(rng), unit(rng));
    const glm::vec3 to = light - o;
    const glm::vec3 d = glm::normalize(to);
    rays.push_back(GrRay{o.x, o.y, o.z, 1e-4f, d.x, d.y, d.z, glm::length(to)});
  }
  return rays;
}

// raysTowards, then rays with the awkward directions: on an axis, on the cube's edges and
// corners (|d| equal on two or three axes, either sign), zero, signed zeros, infinite and
// NaN components, NaN origins and infinite tmax; shuffled.
std::vector<GrRay> raysAround(const glm::vec3& light, size_t count) {
  std::mt19937 rng(13);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  std::vector<GrRay> rays = raysTowards(light, count);
  const float inf = std::numeric_limits<float>::infinity(), nan = std::nanf("");
  const glm::vec3 awkward[] = {
      {1, 0, 0},   {-1, 0, 0},    {0, 1, 0},   {0, -1, 0},    {0, 0, 1},          {0, 0, -1},
      {1, 1, 0},   {-1, 1, 0},    {0, 1, -1},  {1, 0, 1},     {1, 1, 1},          {-1, -1, -1},
      {1, -1, 1},  {-0.0f, 0, 0}, {0, 0, 0},   {0, -0.0f, 2}, {inf, 1, 0},        {inf, inf, 0},
      {nan, 1, 0}, {0, nan, 0},   {1, 2, nan}, {-inf, 0, 0},  {0.5f, 0.5f, -0.5f}};
  for (int round = 0; round < 3; ++round)
    for (const glm::vec3& d : awkward) {
      const glm::vec3 o = light + glm::vec3(unit(rng), unit(rng), unit(rng));
      rays.push_back(GrRay{o.x, o.y, o.z, 0.0f, d.x, d.y, d.z, 2.0f});
    }
  rays.push_back(GrRay{nan, 0, 0, 0, 0, 1, 0, 1});
  rays.push_back(GrRay{0, nan, 0, 0, 0, 1, 0, 1});
  rays.push_back(GrRay{0, 0, 0, 0, 0, -1, 0, inf});
  std::shuffle(rays.begin(), rays.end(), rng);  // the awkward ones in the vector part too
  return rays;
}

struct Pass {
  std::vector<int> face;
  std::vector<float> uv;
  std::vector<double> depth;
  LightRayScan scan;
  explicit Pass(size_t n) : face(n, -1), uv(2 * n, -7.0f), depth(n, -7.0) {}
};

void expectSamePasses(const std::vector<GrRay>& rays, const glm::vec3& light, size_t first,
                      size_t last) {
  Pass one(rays.size()), lanes(rays.size());
  for (size_t r = first; r < last; ++r)
    scanLightRay(rays[r], light, one.face[r], one.uv[2 * r], one.uv[2 * r + 1], one.depth[r],
                 one.scan);
  scanLightRays(rays.data(), first, last, light, lanes.face.data(), lanes.uv.data(),
                lanes.depth.data(), lanes.scan);
  size_t differ = 0;
  for (size_t r = 0; r < rays.size(); ++r) {
    const bool same = one.face[r] == lanes.face[r] && sameBits(one.uv[2 * r], lanes.uv[2 * r]) &&
                      sameBits(one.uv[2 * r + 1], lanes.uv[2 * r + 1]) &&
                      sameBits(one.depth[r], lanes.depth[r]);
    if (!same && ++differ <= 5)
      ADD_FAILURE() << "ray " << r << " (" << rays[r].dx << ", " << rays[r].dy << ", " << rays[r].dz
                    << "): face " << one.face[r] << " / " << lanes.face[r] << ", u "
                    << one.uv[2 * r] << " / " << lanes.uv[2 * r] << ", v " << one.uv[2 * r + 1]
                    << " / " << lanes.uv[2 * r + 1] << ", depth " << one.depth[r] << " / "
                    << lanes.depth[r];
  }
  EXPECT_EQ(differ, 0u) << "rays [" << first << ", " << last << ")";
  EXPECT_TRUE(sameBits(one.scan.miss_squared, lanes.scan.miss_squared));
  EXPECT_TRUE(sameBits(one.scan.reach, lanes.scan.reach));
  EXPECT_TRUE(sameBits(one.scan.min_length_squared, lanes.scan.min_length_squared));
  for (int f = 0; f < 6; ++f) {
    // By value: the lanes meet a face's points in another order, which may keep the other
    // of two signed zeros.
    const FaceWindow &a = one.scan.windows[f], &b = lanes.scan.windows[f];
    EXPECT_EQ(a.count, b.count) << "face " << f;
    EXPECT_EQ(a.umin, b.umin) << "face " << f;
    EXPECT_EQ(a.umax, b.umax) << "face " << f;
    EXPECT_EQ(a.vmin, b.vmin) << "face " << f;
    EXPECT_EQ(a.vmax, b.vmax) << "face " << f;
  }
}

TEST(LightRayScan, LanesGiveTheOneRayValuesBitForBit) {
  const glm::vec3 light(0.25f, 3.0f, -1.5f);
  const std::vector<GrRay> rays = raysAround(light, 4000);
  // Every face holds rays.
  Pass one(rays.size());
  for (size_t r = 0; r < rays.size(); ++r)
    scanLightRay(rays[r], light, one.face[r], one.uv[2 * r], one.uv[2 * r + 1], one.depth[r],
                 one.scan);
  for (int f = 0; f < 6; ++f) ASSERT_GT(one.scan.windows[f].count, 100u) << "face " << f;
  expectSamePasses(rays, light, 0, rays.size());
  // Ranges that start and end inside a vector's worth of rays (the one-ray tail).
  expectSamePasses(rays, light, 3, rays.size() - 5);
  expectSamePasses(rays, light, 17, 17);
  expectSamePasses(rays, light, 40, 47);
}

// The cells of the second pass are FaceWindow::cellOf's, for the faces laid out from the
// first pass's windows, and for points off the windows, huge or not a number (clamped).
TEST(LightRayScan, LanesGiveTheCellsOfCellOf) {
  const glm::vec3 light(0.25f, 3.0f, -1.5f);
  const std::vector<GrRay> rays = raysAround(light, 6000);
  Pass pass(rays.size());
  scanLightRays(rays.data(), 0, rays.size(), light, pass.face.data(), pass.uv.data(),
                pass.depth.data(), pass.scan);
  std::array<FaceWindow, 6> faces = pass.scan.windows;
  // Windows narrower than the rays' (as a window fitted to fewer rays), so that some
  // points fall outside them; the cells counted from row 0 of face 0 on.
  int rows = 0;
  size_t cells = 0;
  for (FaceWindow& w : faces) {
    w.umin *= 0.5f, w.umax *= 0.5f;
    w.layout(rows, cells);
    rows += w.res;
    cells += size_t(w.res) * w.res;
  }
  ASSERT_GT(faces[3].res, 4);
  std::vector<float> uv = pass.uv;
  const float odd[] = {std::nanf(""), 1e30f, -1e30f, std::numeric_limits<float>::infinity(), -0.0f};
  for (size_t k = 0; k < 40; ++k) uv[2 * (k * 97) + (k % 2)] = odd[k % 5];
  std::vector<int> lanes(rays.size(), -1);
  cellsOfLightRays(faces, pass.face.data(), uv.data(), 0, rays.size(), lanes.data());
  size_t differ = 0;
  for (size_t r = 0; r < rays.size(); ++r)
    differ += lanes[r] != int(faces[pass.face[r]].cellOf(uv[2 * r], uv[2 * r + 1]));
  EXPECT_EQ(differ, 0u);
  std::set<int> used(lanes.begin(), lanes.end());
  EXPECT_GT(used.size(), 100u);
  EXPECT_GE(*used.begin(), 0);
  EXPECT_LT(size_t(*used.rbegin()), cells);
}

// The bounds of rays that all end at the light: finite; and the infinite miss of a ray
// whose end is not a number or infinite does not hide in a lane.
TEST(LightRayScan, BoundsOfFiniteAndEndlessRays) {
  const glm::vec3 light(1.0f, 2.0f, 3.0f);
  std::vector<GrRay> rays = raysTowards(light, 300);
  LightRayScan scan;
  std::vector<int> face(rays.size());
  std::vector<float> uv(2 * rays.size());
  std::vector<double> depth(rays.size());
  scanLightRays(rays.data(), 0, rays.size(), light, face.data(), uv.data(), depth.data(), scan);
  EXPECT_TRUE(std::isfinite(scan.miss_squared));
  EXPECT_LT(scan.miss_squared, 1e-8f);  // every end within rounding of the light
  EXPECT_GT(scan.min_length_squared, 0.99f);
  // A ray whose end is not a number ends nowhere near the light either.
  rays[42].dx = std::nanf("");
  LightRayScan no_end;
  scanLightRays(rays.data(), 0, rays.size(), light, face.data(), uv.data(), depth.data(), no_end);
  EXPECT_EQ(no_end.miss_squared, std::numeric_limits<float>::infinity());
  EXPECT_EQ(no_end.min_length_squared, 0.0f);
  rays[42].dx = rays[43].dx;
  rays[137].tmax = std::numeric_limits<float>::infinity();
  LightRayScan endless;
  scanLightRays(rays.data(), 0, rays.size(), light, face.data(), uv.data(), depth.data(), endless);
  EXPECT_EQ(endless.miss_squared, std::numeric_limits<float>::infinity());
  EXPECT_EQ(endless.reach, std::numeric_limits<float>::infinity());
}

}  // namespace
}  // namespace gridrt
