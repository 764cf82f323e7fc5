// The 3D-DDA of kernels/common/grid_dda.h against an independent double-precision
// reference (per-voxel slab tests over every voxel of the grid), its interval bookkeeping,
// the degenerate rays (axis-parallel with +-0 components, through edges and corners,
// starting on faces, non-finite), and computeTraversalLists against a plain DDA walk.
#include "grid_dda.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <random>
#include <string>
#include <tuple>
#include <vector>

#include "dda_packet.h"
#include "parallel_loops.h"
#include "prepared_triangles.h"
#include "scene.h"
#include "traversal_lists.h"
#include "uniform_grid.h"

namespace gridrt {
namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();
constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

GrGridInfo makeGrid(glm::vec3 min, glm::vec3 cell, glm::ivec3 n) {
  GrGridInfo g{};
  g.minx = min.x;
  g.miny = min.y;
  g.minz = min.z;
  g.cellx = cell.x;
  g.celly = cell.y;
  g.cellz = cell.z;
  g.nx = n.x;
  g.ny = n.y;
  g.nz = n.z;
  return g;
}

// 4 x 5 x 6 voxels; every boundary min + k * cell is exact in float, so the reference's
// planes are exactly the DDA's.
GrGridInfo smallGrid() { return makeGrid({-1.5f, -2.0f, 0.25f}, {0.5f, 0.75f, 0.625f}, {4, 5, 6}); }

struct Ray {
  glm::vec3 o, d;
  float tmin = 0.0f, tmax = kInf;
};

struct Visit {
  glm::ivec3 v;
  float t_enter, t_exit;
};

bool stateHasNaN(const GrDda& s) {
  for (float f :
       {s.t_enter, s.t_exit, s.t_end, s.ox, s.oy, s.oz, s.idx, s.idy, s.idz, s.tnx, s.tny, s.tnz})
    if (std::isnan(f)) return true;
  return false;
}

// Walks the DDA; fails the test on NaN in the state or on more steps than the grid allows.
std::vector<Visit> walk(const GrGridInfo& g, const Ray& r, bool* began = nullptr) {
  std::vector<Visit> out;
  GrDda s;
  int ok = gr_dda_begin(&g, r.o.x, r.o.y, r.o.z, r.d.x, r.d.y, r.d.z, r.tmin, r.tmax, &s);
  if (began) *began = ok != 0;
  if (!ok) return out;
  const int limit = g.nx + g.ny + g.nz + 1;
  do {
    EXPECT_FALSE(stateHasNaN(s)) << "NaN in the DDA state at step " << out.size();
    EXPECT_GE(s.ix, 0);
    EXPECT_LT(s.ix, g.nx);
    EXPECT_GE(s.iy, 0);
    EXPECT_LT(s.iy, g.ny);
    EXPECT_GE(s.iz, 0);
    EXPECT_LT(s.iz, g.nz);
    out.push_back({{s.ix, s.iy, s.iz}, s.t_enter, s.t_exit});
    if (int(out.size()) > limit) {
      ADD_FAILURE() << "DDA did not stop after " << limit << " voxels";
      break;
    }
  } while (gr_dda_step(&g, &s));
  return out;
}

struct RefVoxel {
  glm::ivec3 v;
  double t0, t1;  // the ray's parameter range inside the closed box
  bool interior;  // the ray passes through the open box over a positive length
};

// Every voxel whose closed box (grown by `grow`) the segment [tmin, tmax] of the ray meets,
// by entry distance.
std::vector<RefVoxel> reference(const GrGridInfo& g, const Ray& r, double grow = 0.0) {
  const double mins[3] = {g.minx, g.miny, g.minz};
  const double cells[3] = {g.cellx, g.celly, g.cellz};
  const double o[3] = {r.o.x, r.o.y, r.o.z};
  const double d[3] = {r.d.x, r.d.y, r.d.z};
  std::vector<RefVoxel> out;
  for (int z = 0; z < g.nz; ++z)
    for (int y = 0; y < g.ny; ++y)
      for (int x = 0; x < g.nx; ++x) {
        const int idx[3] = {x, y, z};
        double t0 = r.tmin, t1 = r.tmax;
        bool hit = true, open = true;
        for (int a = 0; a < 3 && hit; ++a) {
          double lo = mins[a] + idx[a] * cells[a] - grow, hi = lo + cells[a] + 2.0 * grow;
          if (d[a] == 0.0) {
            if (o[a] < lo || o[a] > hi) hit = false;
            if (!(o[a] > lo && o[a] < hi)) open = false;
          } else {
            double ta = (lo - o[a]) / d[a], tb = (hi - o[a]) / d[a];
            t0 = std::max(t0, std::min(ta, tb));
            t1 = std::min(t1, std::max(ta, tb));
          }
        }
        if (hit && t0 <= t1) out.push_back({{x, y, z}, t0, t1, open && t0 < t1});
      }
  std::sort(out.begin(), out.end(), [](const RefVoxel& a, const RefVoxel& b) {
    return std::tie(a.t0, a.t1) < std::tie(b.t0, b.t1);
  });
  return out;
}

std::string str(const Ray& r) {
  char buf[256];
  std::snprintf(buf, sizeof buf, "ray o=(%.9g,%.9g,%.9g) d=(%.9g,%.9g,%.9g) t=[%.9g,%.9g]", r.o.x,
                r.o.y, r.o.z, r.d.x, r.d.y, r.d.z, r.tmin, r.tmax);
  return buf;
}

std::string str(const glm::ivec3& v) {
  return "(" + std::to_string(v.x) + "," + std::to_string(v.y) + "," + std::to_string(v.z) + ")";
}

double tolerance(double t) { return 1e-5 * (1.0 + std::fabs(t)); }

// A generic ray passes no edge or corner: no two boundary crossings (nor the range ends)
// closer than `gap`, so float rounding cannot reorder them.
bool isGeneric(const std::vector<RefVoxel>& ref, double gap = 1e-4) {
  for (const auto& v : ref)
    if (v.t1 - v.t0 < gap) return false;
  return true;
}

// The properties every traversal has, generic or not:
//  - the intervals chain: t_enter <= t_exit, each t_enter is the previous t_exit bit for
//    bit, the first t_enter >= tmin, the last t_exit <= tmax;
//  - the walk starts where the ray enters the grid and ends where it leaves (or tmax);
//  - each step moves one voxel along one axis, in the direction of the ray;
//  - every visited voxel is touched by the ray (closed box; grown by 1e-5 so that a ray
//    passing within float rounding of an edge may take either side), over its DDA
//    interval, in order of entry;
//  - every voxel whose interior the ray crosses over a length that float rounding cannot
//    erase (1e-4) is visited.
void expectConsistent(const GrGridInfo& g, const Ray& r, const std::vector<Visit>& seq,
                      const std::vector<RefVoxel>& ref) {
  SCOPED_TRACE(str(r));
  ASSERT_EQ(seq.empty(), ref.empty())
      << "DDA visits " << seq.size() << ", reference " << ref.size();
  if (seq.empty()) return;
  std::map<std::tuple<int, int, int>, RefVoxel> touched;
  for (const auto& v : reference(g, r, 1e-5)) touched[{v.v.x, v.v.y, v.v.z}] = v;
  double ref_begin = ref.front().t0, ref_end = ref.front().t1;
  for (const auto& v : ref) {
    ref_begin = std::min(ref_begin, v.t0);
    ref_end = std::max(ref_end, v.t1);
  }
  EXPECT_GE(seq.front().t_enter, r.tmin);
  EXPECT_LE(seq.back().t_exit, r.tmax);
  EXPECT_NEAR(seq.front().t_enter, ref_begin, tolerance(ref_begin));
  EXPECT_NEAR(seq.back().t_exit, ref_end, tolerance(ref_end));
  const glm::ivec3 step(r.d.x > 0 ? 1 : (r.d.x < 0 ? -1 : 0), r.d.y > 0 ? 1 : (r.d.y < 0 ? -1 : 0),
                        r.d.z > 0 ? 1 : (r.d.z < 0 ? -1 : 0));
  double last_t0 = -std::numeric_limits<double>::infinity();
  for (size_t i = 0; i < seq.size(); ++i) {
    const Visit& s = seq[i];
    SCOPED_TRACE("visit " + std::to_string(i) + " voxel " + str(s.v));
    EXPECT_LE(s.t_enter, s.t_exit);
    if (i > 0) {
      EXPECT_EQ(std::memcmp(&s.t_enter, &seq[i - 1].t_exit, sizeof(float)), 0)
          << "t_enter " << s.t_enter << " != previous t_exit " << seq[i - 1].t_exit;
      glm::ivec3 dv = s.v - seq[i - 1].v;
      int moved = (dv.x != 0) + (dv.y != 0) + (dv.z != 0);
      EXPECT_EQ(moved, 1);
      for (int a = 0; a < 3; ++a)
        if (dv[a] != 0) {
          EXPECT_EQ(dv[a], step[a]) << "axis " << a;
        }
    }
    auto it = touched.find({s.v.x, s.v.y, s.v.z});
    if (it == touched.end()) {
      ADD_FAILURE() << "visits a voxel the ray does not touch";
      continue;
    }
    const RefVoxel& rv = it->second;
    EXPECT_GE(rv.t0, last_t0 - tolerance(last_t0)) << "out of entry order";
    last_t0 = rv.t0;
    // The DDA's interval lies inside the reference interval of the voxel.
    EXPECT_GE(s.t_enter, rv.t0 - tolerance(rv.t0));
    EXPECT_LE(s.t_exit, rv.t1 + tolerance(rv.t1));
  }
  for (const auto& v : ref) {
    if (!v.interior || v.t1 - v.t0 < 1e-4) continue;
    bool found = std::any_of(seq.begin(), seq.end(), [&](const Visit& s) { return s.v == v.v; });
    EXPECT_TRUE(found) << "skips voxel " << str(v.v) << " crossed over [" << v.t0 << ", " << v.t1
                       << "]";
  }
}

// For a generic ray the DDA's sequence is exactly the reference's, with matching intervals.
void expectSameAsReference(const GrGridInfo& g, const Ray& r, const std::vector<Visit>& seq,
                           const std::vector<RefVoxel>& ref) {
  expectConsistent(g, r, seq, ref);
  SCOPED_TRACE(str(r));
  ASSERT_EQ(seq.size(), ref.size());
  for (size_t i = 0; i < seq.size(); ++i) {
    EXPECT_EQ(seq[i].v, ref[i].v) << "visit " << i;
    EXPECT_NEAR(seq[i].t_enter, ref[i].t0, tolerance(ref[i].t0)) << "visit " << i;
    EXPECT_NEAR(seq[i].t_exit, ref[i].t1, tolerance(ref[i].t1)) << "visit " << i;
  }
}

glm::vec3 randomDirection(std::mt19937& rng) {
  std::normal_distribution<float> gauss(0.0f, 1.0f);
  glm::vec3 d;
  do d = glm::vec3(gauss(rng), gauss(rng), gauss(rng));
  while (glm::length(d) < 1e-3f);
  return glm::normalize(d);
}

// Origins in the grid box grown by a grid extent on every side: inside and outside.
glm::vec3 randomOrigin(std::mt19937& rng, const GrGridInfo& g) {
  glm::vec3 lo(g.minx, g.miny, g.minz);
  glm::vec3 ext(g.nx * g.cellx, g.ny * g.celly, g.nz * g.cellz);
  std::uniform_real_distribution<float> u(-1.0f, 2.0f);
  return lo + ext * glm::vec3(u(rng), u(rng), u(rng));
}

// Half the time a random direction, otherwise towards a random point of the grid box.
glm::vec3 someDirection(std::mt19937& rng, const GrGridInfo& g, const glm::vec3& o) {
  if (rng() % 2) return randomDirection(rng);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  glm::vec3 target(g.minx + g.nx * g.cellx * u(rng), g.miny + g.ny * g.celly * u(rng),
                   g.minz + g.nz * g.cellz * u(rng));
  glm::vec3 d = target - o;
  return glm::length(d) > 1e-3f ? glm::normalize(d) : randomDirection(rng);
}

TEST(GridDda, RandomRaysVisitExactlyTheVoxelsTheyPierceInOrder) {
  const GrGridInfo g = smallGrid();
  std::mt19937 rng(42);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  int generic = 0, hits = 0, inside = 0;
  const int kRays = 4000;
  for (int i = 0; i < kRays; ++i) {
    Ray r;
    r.o = randomOrigin(rng, g);
    r.d = someDirection(rng, g, r.o);
    // A quarter with a finite [tmin, tmax] that may start or end inside the grid.
    if (i % 4 == 1) {
      r.tmin = 3.0f * u(rng);
      r.tmax = r.tmin + 6.0f * u(rng);
    }
    auto ref = reference(g, r);
    auto seq = walk(g, r);
    if (!isGeneric(ref)) {
      expectConsistent(g, r, seq, ref);
      continue;
    }
    ++generic;
    hits += !ref.empty();
    inside += !ref.empty() && ref.front().t0 == r.tmin;
    expectSameAsReference(g, r, seq, ref);
    if (::testing::Test::HasFailure()) break;
  }
  // The sample is meaningful: nearly all generic, many hits, some starting inside.
  EXPECT_GT(generic, kRays * 95 / 100);
  EXPECT_GT(hits, kRays / 5);
  EXPECT_GT(inside, kRays / 50);
}

TEST(GridDda, RandomRaysWithZeroDirectionComponentsVisitExactlyTheirRowOrPlane) {
  const GrGridInfo g = smallGrid();
  std::mt19937 rng(7);
  int generic = 0, hits = 0;
  for (int i = 0; i < 3000; ++i) {
    Ray r;
    r.o = randomOrigin(rng, g);
    r.d = someDirection(rng, g, r.o);
    // Zero one or two components, as +0 or -0.
    int zeros = 1 + i % 2;
    for (int k = 0; k < zeros; ++k) r.d[(i / 2 + k) % 3] = (i / 6) % 2 ? -0.0f : 0.0f;
    r.d = glm::normalize(r.d);
    // Keep the origin inside the grid's slab on the zeroed axes half the time.
    if (i % 4 < 2)
      for (int a = 0; a < 3; ++a)
        if (r.d[a] == 0.0f) {
          const float lo[3] = {g.minx, g.miny, g.minz};
          const float ext[3] = {g.nx * g.cellx, g.ny * g.celly, g.nz * g.cellz};
          r.o[a] = lo[a] + ext[a] * std::uniform_real_distribution<float>(0.01f, 0.99f)(rng);
        }
    auto ref = reference(g, r);
    auto seq = walk(g, r);
    if (!isGeneric(ref)) {
      expectConsistent(g, r, seq, ref);
      continue;
    }
    ++generic;
    hits += !ref.empty();
    expectSameAsReference(g, r, seq, ref);
    if (::testing::Test::HasFailure()) break;
  }
  EXPECT_GT(generic, 2800);
  EXPECT_GT(hits, 800);
}

TEST(GridDda, RandomRaysStartingOnVoxelFacesVisitEveryVoxelTheyCross) {
  const GrGridInfo g = smallGrid();
  std::mt19937 rng(99);
  for (int i = 0; i < 2000; ++i) {
    Ray r;
    r.o = randomOrigin(rng, g);
    r.d = someDirection(rng, g, r.o);
    // Snap one coordinate onto a boundary plane (grid faces included).
    int a = i % 3;
    const float lo[3] = {g.minx, g.miny, g.minz}, cell[3] = {g.cellx, g.celly, g.cellz};
    const int n[3] = {g.nx, g.ny, g.nz};
    int k = std::uniform_int_distribution<int>(0, n[a])(rng);
    r.o[a] = lo[a] + float(k) * cell[a];
    auto ref = reference(g, r);
    auto seq = walk(g, r);
    expectConsistent(g, r, seq, ref);
    if (::testing::Test::HasFailure()) break;
  }
}

TEST(GridDda, IntervalsChainExactlyAndStayWithinTminTmax) {
  const GrGridInfo g = makeGrid({0.1f, -0.3f, 1.7f}, {0.37f, 0.29f, 0.41f}, {7, 9, 5});
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  int visited = 0;
  for (int i = 0; i < 3000; ++i) {
    Ray r;
    r.o = randomOrigin(rng, g);
    r.d = someDirection(rng, g, r.o);
    if (i % 2) {
      r.tmin = 2.0f * u(rng);
      r.tmax = r.tmin + 4.0f * u(rng);
    }
    auto seq = walk(g, r);
    visited += int(seq.size());
    for (size_t j = 0; j < seq.size(); ++j) {
      ASSERT_LE(seq[j].t_enter, seq[j].t_exit) << str(r);
      if (j > 0) {
        ASSERT_EQ(std::memcmp(&seq[j].t_enter, &seq[j - 1].t_exit, sizeof(float)), 0) << str(r);
      }
    }
    if (!seq.empty()) {
      ASSERT_GE(seq.front().t_enter, r.tmin) << str(r);
      ASSERT_LE(seq.back().t_exit, r.tmax) << str(r);
    }
  }
  EXPECT_GT(visited, 3000);
}

TEST(GridDda, AxisParallelRaysVisitExactlyTheirRowWithoutNaN) {
  const GrGridInfo g = smallGrid();
  const float mz = 0.25f + 2.2f * 0.625f;  // inside voxel z = 2
  const float my = -2.0f + 3.4f * 0.75f;   // inside voxel y = 3
  const float mx = -1.5f + 1.3f * 0.5f;    // inside voxel x = 1
  struct Case {
    glm::vec3 o, d;
    std::vector<glm::ivec3> want;
  };
  std::vector<Case> cases = {
      {{-5.0f, my, mz}, {1.0f, 0.0f, 0.0f}, {{0, 3, 2}, {1, 3, 2}, {2, 3, 2}, {3, 3, 2}}},
      {{-5.0f, my, mz}, {1.0f, -0.0f, 0.0f}, {{0, 3, 2}, {1, 3, 2}, {2, 3, 2}, {3, 3, 2}}},
      {{-5.0f, my, mz}, {1.0f, -0.0f, -0.0f}, {{0, 3, 2}, {1, 3, 2}, {2, 3, 2}, {3, 3, 2}}},
      {{5.0f, my, mz}, {-1.0f, -0.0f, 0.0f}, {{3, 3, 2}, {2, 3, 2}, {1, 3, 2}, {0, 3, 2}}},
      {{mx, 9.0f, mz},
       {0.0f, -1.0f, 0.0f},
       {{1, 4, 2}, {1, 3, 2}, {1, 2, 2}, {1, 1, 2}, {1, 0, 2}}},
      {{mx, 9.0f, mz},
       {-0.0f, -1.0f, -0.0f},
       {{1, 4, 2}, {1, 3, 2}, {1, 2, 2}, {1, 1, 2}, {1, 0, 2}}},
      {{mx, my, -3.0f},
       {0.0f, 0.0f, 1.0f},
       {{1, 3, 0}, {1, 3, 1}, {1, 3, 2}, {1, 3, 3}, {1, 3, 4}, {1, 3, 5}}},
      {{mx, my, -3.0f},
       {-0.0f, -0.0f, 1.0f},
       {{1, 3, 0}, {1, 3, 1}, {1, 3, 2}, {1, 3, 3}, {1, 3, 4}, {1, 3, 5}}},
      // Starting inside: the rest of the row only.
      {{mx, my, mz}, {0.0f, 0.0f, 1.0f}, {{1, 3, 2}, {1, 3, 3}, {1, 3, 4}, {1, 3, 5}}},
      {{mx, my, mz}, {-0.0f, 0.0f, -1.0f}, {{1, 3, 2}, {1, 3, 1}, {1, 3, 0}}},
  };
  for (const auto& c : cases) {
    Ray r{c.o, c.d};
    SCOPED_TRACE(str(r));
    bool began = false;
    auto seq = walk(g, r, &began);
    ASSERT_TRUE(began);
    ASSERT_EQ(seq.size(), c.want.size());
    for (size_t i = 0; i < seq.size(); ++i) {
      EXPECT_EQ(seq[i].v, c.want[i]) << "visit " << i;
      EXPECT_TRUE(std::isfinite(seq[i].t_enter));
      EXPECT_TRUE(std::isfinite(seq[i].t_exit));
      EXPECT_LT(seq[i].t_enter, seq[i].t_exit) << "visit " << i;
    }
    expectSameAsReference(g, r, seq, reference(g, r));
  }
  // Parallel to an axis, lying exactly in the grid's outer face: the closed boundary row.
  for (float y : {g.miny, g.miny + g.ny * g.celly}) {
    Ray r{{-5.0f, y, mz}, {1.0f, -0.0f, 0.0f}};
    SCOPED_TRACE(str(r));
    auto seq = walk(g, r);
    expectConsistent(g, r, seq, reference(g, r));
    ASSERT_EQ(seq.size(), 4u);
    for (int i = 0; i < 4; ++i) EXPECT_EQ(seq[i].v, glm::ivec3(i, y == g.miny ? 0 : g.ny - 1, 2));
  }
  // Parallel to an axis but outside the grid's slab: misses.
  for (glm::vec3 d : {glm::vec3(1, 0, 0), glm::vec3(1, -0.0f, 0), glm::vec3(0, 0, -1)}) {
    Ray r{{-5.0f, 100.0f, mz}, d};
    if (d.z != 0) r.o = {mx, 100.0f, 9.0f};
    bool began = true;
    EXPECT_TRUE(walk(g, r, &began).empty());
    EXPECT_FALSE(began) << str(r);
  }
}

TEST(GridDda, RayAlongAVoxelEdgeVisitsAWholeColumnTouchingTheEdge) {
  const GrGridInfo g = smallGrid();
  // The edge x = min.x + cell.x, y = min.y + cell.y, along z.
  for (float dz : {1.0f, -1.0f}) {
    Ray r{{g.minx + g.cellx, g.miny + g.celly, dz > 0 ? -1.0f : 6.0f}, {0.0f, 0.0f, dz}};
    SCOPED_TRACE(str(r));
    auto seq = walk(g, r);
    auto ref = reference(g, r);
    expectConsistent(g, r, seq, ref);
    ASSERT_EQ(int(seq.size()), g.nz);
    for (int i = 0; i < g.nz; ++i) {
      EXPECT_EQ(seq[i].v.z, dz > 0 ? i : g.nz - 1 - i);
      EXPECT_EQ(seq[i].v.x, seq[0].v.x);
      EXPECT_EQ(seq[i].v.y, seq[0].v.y);
    }
    // One of the four columns sharing the edge.
    EXPECT_TRUE(seq[0].v.x == 0 || seq[0].v.x == 1);
    EXPECT_TRUE(seq[0].v.y == 0 || seq[0].v.y == 1);
  }
  // An oblique ray in the plane z = const through the edges (k, k) of a unit grid.
  const GrGridInfo unit = makeGrid({0, 0, 0}, {1, 1, 1}, {4, 5, 6});
  Ray r{{-0.5f, -0.5f, 2.5f}, glm::normalize(glm::vec3(1.0f, 1.0f, 0.0f))};
  auto seq = walk(unit, r);
  expectConsistent(unit, r, seq, reference(unit, r));
  for (int k = 0; k < 4; ++k) {
    bool found = std::any_of(seq.begin(), seq.end(),
                             [&](const Visit& s) { return s.v == glm::ivec3(k, k, 2); });
    EXPECT_TRUE(found) << "diagonal voxel " << k;
  }
}

TEST(GridDda, DiagonalRayThroughCornersVisitsEveryDiagonalVoxelInOrder) {
  const GrGridInfo g = makeGrid({0, 0, 0}, {1, 1, 1}, {4, 5, 6});
  for (bool reverse : {false, true}) {
    Ray r{{-0.5f, -0.5f, -0.5f}, glm::normalize(glm::vec3(1.0f, 1.0f, 1.0f))};
    if (reverse) r = Ray{{4.5f, 4.5f, 4.5f}, -glm::normalize(glm::vec3(1.0f, 1.0f, 1.0f))};
    SCOPED_TRACE(str(r));
    ASSERT_EQ(r.d.x, r.d.y);
    ASSERT_EQ(r.d.x, r.d.z);
    auto seq = walk(g, r);
    auto ref = reference(g, r);
    expectConsistent(g, r, seq, ref);
    // The diagonal voxels (k, k, k), k = 0..3, all appear, in order.
    std::vector<int> diagonal;
    for (const auto& s : seq)
      if (s.v.x == s.v.y && s.v.y == s.v.z) diagonal.push_back(s.v.x);
    EXPECT_EQ(diagonal, reverse ? std::vector<int>({3, 2, 1, 0}) : std::vector<int>({0, 1, 2, 3}));
    // Only the diagonal voxels have a positive length; between two of them the DDA passes
    // two zero-length voxels (one axis at a time).
    for (const auto& s : seq) {
      bool on_diagonal = s.v.x == s.v.y && s.v.y == s.v.z;
      EXPECT_EQ(on_diagonal, s.t_exit > s.t_enter) << str(s.v);
    }
    if (!reverse) {
      EXPECT_EQ(seq.size(), size_t(4 + 3 * 2));
    }
  }
}

TEST(GridDda, RayStartingOnAVoxelFaceStartsInTheVoxelAhead) {
  const GrGridInfo g = smallGrid();
  const float face = g.minx + 2.0f * g.cellx;  // between voxels x = 1 and x = 2
  const float my = -2.0f + 2.5f * 0.75f, mz = 0.25f + 3.5f * 0.625f;
  {
    Ray r{{face, my, mz}, {1.0f, 0.0f, 0.0f}};
    auto seq = walk(g, r);
    expectConsistent(g, r, seq, reference(g, r));
    ASSERT_EQ(seq.size(), 2u);
    EXPECT_EQ(seq[0].v, glm::ivec3(2, 2, 3));
    EXPECT_EQ(seq[1].v, glm::ivec3(3, 2, 3));
    EXPECT_EQ(seq[0].t_enter, 0.0f);
  }
  {
    Ray r{{face, my, mz}, {-1.0f, 0.0f, 0.0f}};
    auto seq = walk(g, r);
    expectConsistent(g, r, seq, reference(g, r));
    // Visits, with positive length, exactly x = 1 then 0 (a zero-length x = 2 first is fine).
    std::vector<int> xs;
    for (const auto& s : seq)
      if (s.t_exit > s.t_enter) xs.push_back(s.v.x);
    EXPECT_EQ(xs, std::vector<int>({1, 0}));
  }
  {
    Ray r{{face, my, mz}, glm::normalize(glm::vec3(0.3f, -0.4f, 0.5f))};
    auto seq = walk(g, r);
    expectConsistent(g, r, seq, reference(g, r));
    ASSERT_FALSE(seq.empty());
    EXPECT_EQ(seq[0].v, glm::ivec3(2, 2, 3));
  }
}

TEST(GridDda, RayStartingInsideTheGridStartsInItsVoxelAtTmin) {
  const GrGridInfo g = smallGrid();
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(0.05f, 0.95f);
  for (int i = 0; i < 200; ++i) {
    glm::ivec3 v(i % 4, (i / 4) % 5, (i / 20) % 6);
    Ray r{{g.minx + (v.x + u(rng)) * g.cellx, g.miny + (v.y + u(rng)) * g.celly,
           g.minz + (v.z + u(rng)) * g.cellz},
          randomDirection(rng)};
    auto seq = walk(g, r);
    ASSERT_FALSE(seq.empty()) << str(r);
    EXPECT_EQ(seq[0].v, v) << str(r);
    EXPECT_EQ(seq[0].t_enter, 0.0f) << str(r);
    expectConsistent(g, r, seq, reference(g, r));
  }
}

TEST(GridDda, RaysMissingTheGridOrNotFiniteReturnZero) {
  const GrGridInfo g = smallGrid();
  GrDda s;
  // Pointing away, passing beside, behind the origin, segment ending before the grid.
  EXPECT_EQ(gr_dda_begin(&g, -5, 0, 1, -1, 0, 0, 0, kInf, &s), 0);
  EXPECT_EQ(gr_dda_begin(&g, -5, 10, 1, 1, 0, 0, 0, kInf, &s), 0);
  EXPECT_EQ(gr_dda_begin(&g, -5, 0, 1, 0.6f, 0.8f, 0, 0, kInf, &s), 0);
  EXPECT_EQ(gr_dda_begin(&g, -5, 0, 1, 1, 0, 0, 0, 3.0f, &s), 0);     // grid starts at x = -1.5
  EXPECT_EQ(gr_dda_begin(&g, -5, 0, 1, 1, 0, 0, 9.0f, kInf, &s), 0);  // starts past it
  EXPECT_EQ(gr_dda_begin(&g, -5, 0, 1, 1, 0, 0, 2.0f, 1.0f, &s), 0);  // empty range
  // The same ray, well-formed, hits.
  EXPECT_EQ(gr_dda_begin(&g, -5, 0, 1, 1, 0, 0, 0, kInf, &s), 1);
  EXPECT_EQ(gr_dda_begin(&g, -5, 0, 1, 1, 0, 0, kNaN, kInf, &s), 0);
  EXPECT_EQ(gr_dda_begin(&g, -5, 0, 1, 1, 0, 0, 0, kNaN, &s), 0);
  EXPECT_EQ(gr_dda_begin(&g, -5, 0, 1, 1, 0, 0, kInf, kInf, &s), 0);
  for (float bad : {kNaN, kInf, -kInf}) {
    for (int c = 0; c < 6; ++c) {
      float v[6] = {-5, 0, 1, 1, 0, 0};
      v[c] = bad;
      EXPECT_EQ(gr_dda_begin(&g, v[0], v[1], v[2], v[3], v[4], v[5], 0, kInf, &s), 0)
          << "component " << c << " = " << bad;
    }
  }
}

// A subnormal direction component (1/d overflows to inf) with the origin on a boundary
// plane of that axis: walked as if the component were zero, not collapsed by 0 * inf.
TEST(GridDda, SubnormalDirectionComponentIsWalkedAsZero) {
  const GrGridInfo g = smallGrid();
  const float mz = 0.25f + 1.5f * 0.625f;
  for (float tiny : {1e-40f, -1e-40f, 1e-45f, -1e-45f}) {
    for (float oy : {g.miny + 2.0f * g.celly, g.miny, g.miny + g.ny * g.celly, -0.6f}) {
      Ray r{{-5.0f, oy, mz}, {1.0f, tiny, 0.0f}};
      Ray zero{{-5.0f, oy, mz}, {1.0f, 0.0f, 0.0f}};
      SCOPED_TRACE(str(r));
      auto seq = walk(g, r);
      auto want = walk(g, zero);
      ASSERT_EQ(seq.size(), 4u);
      ASSERT_EQ(seq.size(), want.size());
      for (size_t i = 0; i < seq.size(); ++i) {
        EXPECT_EQ(seq[i].v, want[i].v) << "visit " << i;
        EXPECT_EQ(seq[i].t_enter, want[i].t_enter) << "visit " << i;
        EXPECT_EQ(seq[i].t_exit, want[i].t_exit) << "visit " << i;
      }
    }
  }
  // A subnormal z component, the origin on a z boundary plane.
  for (float tiny : {1e-40f, -1e-40f}) {
    Ray r{{-5.0f, -0.6f, g.minz + 3.0f * g.cellz}, {1.0f, 0.0f, tiny}};
    auto seq = walk(g, r);
    ASSERT_EQ(seq.size(), 4u) << str(r);
    for (const auto& v : seq) EXPECT_LT(v.t_enter, v.t_exit) << str(r);
  }
  // Along z, origin on an interior edge, subnormal x and y components.
  Ray r{{g.minx + g.cellx, g.miny + g.celly, -3.0f}, {-1e-40f, 1e-40f, 1.0f}};
  auto seq = walk(g, r);
  EXPECT_EQ(int(seq.size()), g.nz) << str(r);
}

TEST(GridDda, TmaxInsideTheGridStopsTheWalkThere) {
  const GrGridInfo g = smallGrid();
  const float my = -2.0f + 2.5f * 0.75f, mz = 0.25f + 3.5f * 0.625f;
  // From x = -5 along +x the grid starts at t = 3.5; voxel x = 2 spans t in [4.5, 5].
  Ray r{{-5.0f, my, mz}, {1.0f, 0.0f, 0.0f}, 0.0f, 4.7f};
  auto seq = walk(g, r);
  ASSERT_EQ(seq.size(), 3u);
  EXPECT_EQ(seq[2].v, glm::ivec3(2, 2, 3));
  EXPECT_EQ(seq.back().t_exit, 4.7f);
  expectSameAsReference(g, r, seq, reference(g, r));
  // tmax exactly on a boundary: the voxel beyond it is not entered with a positive length.
  r.tmax = 4.5f;
  seq = walk(g, r);
  ASSERT_FALSE(seq.empty());
  EXPECT_EQ(seq.back().t_exit, 4.5f);
  for (const auto& s : seq)
    if (s.v.x == 2) {
      EXPECT_EQ(s.t_enter, s.t_exit);
    }
  expectConsistent(g, r, seq, reference(g, r));
  // Oblique: ends inside, at tmax.
  Ray o{{-2.0f, -2.5f, 0.0f}, glm::normalize(glm::vec3(0.4f, 0.7f, 0.6f)), 0.0f, 3.0f};
  seq = walk(g, o);
  ASSERT_FALSE(seq.empty());
  EXPECT_EQ(seq.back().t_exit, 3.0f);
  expectConsistent(g, o, seq, reference(g, o));
}

// The lists of rays[0..count) against the scalar DDA walk filtered to non-empty voxels,
// ray by ray, bit for bit.
void expectListsMatchTheWalk(const UniformGrid& grid, const GrRay* rays, size_t count,
                             const TraversalLists& lists) {
  ASSERT_EQ(lists.rayCount(), count);
  ASSERT_EQ(lists.begin.size(), count + 1);
  ASSERT_EQ(lists.begin[0], 0);
  for (size_t r = 0; r < count; ++r) ASSERT_LE(lists.begin[r], lists.begin[r + 1]);
  size_t entries = 0;
  for (size_t c = 0; c * kListChunkRays < count; ++c) entries += lists.chunks[c].size();
  ASSERT_EQ(size_t(lists.begin[count]), entries);
  for (size_t r = 0; r < count; ++r) {
    const GrRay& ray = rays[r];
    std::vector<ListEntry> want;
    GrDda s;
    if (gr_dda_begin(&grid.info, ray.ox, ray.oy, ray.oz, ray.dx, ray.dy, ray.dz, ray.tmin, ray.tmax,
                     &s)) {
      do {
        int pe = grid.pe_of_voxel[s.ix + grid.info.nx * (s.iy + grid.info.ny * s.iz)];
        if (pe >= 0) want.push_back({pe, s.t_enter, s.t_exit});
      } while (gr_dda_step(&grid.info, &s));
    }
    ASSERT_EQ(lists.lengthOf(r), int(want.size())) << "ray " << r;
    for (size_t k = 0; k < want.size(); ++k) {
      const ListEntry& e = lists.entriesOf(r)[k];
      ASSERT_EQ(e.pe, want[k].pe) << "ray " << r << " entry " << k;
      ASSERT_EQ(std::memcmp(&e.t_enter, &want[k].t_enter, sizeof(float)), 0) << "ray " << r;
      ASSERT_EQ(std::memcmp(&e.t_exit, &want[k].t_exit, sizeof(float)), 0) << "ray " << r;
      if (k > 0) {
        ASSERT_LE(lists.entriesOf(r)[k - 1].t_exit, e.t_enter);
      }
    }
  }
}

UniformGrid randomTriangleGrid(std::mt19937& rng, int triangles, glm::ivec3 dims) {
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  Scene scene;
  for (int t = 0; t < triangles; ++t) {
    glm::vec3 c(4.0f * u(rng), 3.0f * u(rng), 2.0f * u(rng));
    for (int k = 0; k < 3; ++k)
      scene.positions.push_back(c + 0.3f * glm::vec3(u(rng) - 0.5f, u(rng) - 0.5f, u(rng) - 0.5f));
  }
  auto tris = prepareTriangles(scene);
  GridSettings settings;
  settings.automatic = false;
  settings.dims = dims;
  return buildUniformGrid(tris, sceneBounds(scene), settings);
}

// computeTraversalLists = the DDA walk filtered to non-empty voxels, ray by ray.
TEST(TraversalLists, MatchTheDdaWalkFilteredToNonEmptyVoxels) {
  std::mt19937 rng(17);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  UniformGrid grid = randomTriangleGrid(rng, 60, {9, 7, 5});
  ASSERT_GT(grid.peCount(), 10);
  ASSERT_LT(size_t(grid.peCount()), grid.voxelCount());  // some voxels are empty

  std::vector<GrRay> rays;
  for (int i = 0; i < 3000; ++i) {
    glm::vec3 o = randomOrigin(rng, grid.info);
    glm::vec3 d = someDirection(rng, grid.info, o);
    if (i % 10 == 3) d.y = -0.0f;
    if (i % 10 == 7) d = glm::vec3(0.0f, 0.0f, 1.0f);
    float tmin = i % 3 == 0 ? u(rng) : 0.0f;
    float tmax = i % 5 == 0 ? 1.0f + 5.0f * u(rng) : kInf;
    rays.push_back({o.x, o.y, o.z, tmin, d.x, d.y, d.z, tmax});
  }
  rays.push_back({kNaN, 0, 0, 0, 1, 0, 0, kInf});  // misses

  TraversalLists lists;
  size_t total_entries = 0;
  for (int threads : {1, 3, 8}) {
    const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
    for (size_t count : {rays.size(), size_t(0), size_t(2), rays.size() / 2}) {
      SCOPED_TRACE(std::to_string(threads) + " threads, " + std::to_string(count) + " rays");
      computeTraversalLists(grid, rays.data(), count, lists);  // reuses the scratch
      expectListsMatchTheWalk(grid, rays.data(), count, lists);
      if (count == rays.size()) total_entries = lists.entryCount();
    }
  }
  EXPECT_GT(total_entries, rays.size());  // the rays really pierce PEs
  EXPECT_EQ(lists.rayCount(), rays.size() / 2);
}

// Rays whose components come from the values a DDA trips over (zeros of both signs,
// subnormals, the smallest normal, huge, infinite, NaN), origins on voxel planes, edges
// and corners, and odd intervals (negative, empty, NaN).
std::vector<GrRay> raysThatTripDdas(std::mt19937& rng, const GrGridInfo& g, int count) {
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  const float denorm = std::numeric_limits<float>::denorm_min();
  const float tiny = std::numeric_limits<float>::min();
  const float odd_components[] = {0.0f,   -0.0f, denorm, -denorm, 1e-40f, tiny, -tiny,
                                  1e-30f, 1e30f, -1e30f, kInf,    -kInf,  kNaN};
  const float odd_intervals[] = {0.0f, -1.0f, 1e-30f, 0.5f, 2.0f, kInf, -kInf, kNaN};
  auto pick = [&](const float* values, size_t n) { return values[rng() % n]; };
  std::vector<GrRay> rays;
  for (int i = 0; i < count; ++i) {
    glm::vec3 o = randomOrigin(rng, g);
    glm::vec3 d = someDirection(rng, g, o);
    switch (i % 8) {
      case 0:
        d[rng() % 3] = pick(odd_components, std::size(odd_components));
        break;
      case 1:  // on a voxel plane of each axis
        o = glm::vec3(g.minx + float(rng() % (g.nx + 1)) * g.cellx,
                      g.miny + float(rng() % (g.ny + 1)) * g.celly,
                      g.minz + float(rng() % (g.nz + 1)) * g.cellz);
        break;
      case 2:  // on a plane, along it, through edges
        o[rng() % 3] = g.minx + float(rng() % (g.nx + 1)) * g.cellx;
        d = glm::vec3(float(int(rng() % 3) - 1), float(int(rng() % 3) - 1),
                      float(int(rng() % 3) - 1));
        break;
      case 3:
        o[rng() % 3] = pick(odd_components, std::size(odd_components));
        break;
      case 4: {  // on a voxel plane, moving along it by an odd amount (0 * inf is NaN)
        const int a = rng() % 3;
        const float mins[3] = {g.minx, g.miny, g.minz}, cells[3] = {g.cellx, g.celly, g.cellz};
        const int n[3] = {g.nx, g.ny, g.nz};
        o[a] = mins[a] + float(rng() % (n[a] + 1)) * cells[a];
        d[a] = pick(odd_components, std::size(odd_components));
        break;
      }
      default:
        break;
    }
    float tmin = i % 5 == 0 ? pick(odd_intervals, std::size(odd_intervals)) : 0.0f;
    float tmax = i % 7 == 0 ? pick(odd_intervals, std::size(odd_intervals)) : kInf;
    if (i % 11 == 0) tmax = 10.0f * u(rng);
    rays.push_back({o.x, o.y, o.z, tmin, d.x, d.y, d.z, tmax});
  }
  return rays;
}

// Where methods fail: the rays of raysThatTripDdas. The lists (walked in packets as wide
// as the build's vectors, dda_packet.h) must still equal the scalar walk bit for bit.
TEST(TraversalLists, MatchTheDdaWalkForRaysThatTripDdas) {
  std::mt19937 rng(29);
  UniformGrid grid = randomTriangleGrid(rng, 80, {7, 6, 5});
  const std::vector<GrRay> rays = raysThatTripDdas(rng, grid.info, 200000);
  TraversalLists lists;
  for (size_t count : {rays.size(), size_t(1), size_t(17), size_t(4099)}) {
    SCOPED_TRACE(std::to_string(count) + " rays");
    computeTraversalLists(grid, rays.data(), count, lists);
    expectListsMatchTheWalk(grid, rays.data(), count, lists);
  }
  EXPECT_GT(lists.entryCount(), size_t(1000));  // the rays really pierce PEs
}

// The packet walk at every width the build has (1, 4, 8, 16 lanes) equals the scalar walk
// bit for bit, in full packets and in a last, partial one.
TEST(TraversalLists, PacketWalkOfEveryBuiltWidthMatchesTheDdaWalk) {
  std::mt19937 rng(31);
  UniformGrid grid = randomTriangleGrid(rng, 80, {7, 6, 5});
  const GrGridInfo& g = grid.info;
  const std::vector<GrRay> rays = raysThatTripDdas(rng, g, 20011);
  const int stride = g.nx + g.ny + g.nz;
  int widths = 0;
  for (int lanes : {1, 4, 8, 16}) {
    if (!ddaPacketWidthIsBuilt(lanes)) continue;
    ++widths;
    SCOPED_TRACE(std::to_string(lanes) + " lanes");
    std::vector<int> begin{0};
    std::vector<ListEntry> entries, packet(size_t(lanes) * stride);
    int found[kDdaPacketMaxLanes];
    for (size_t r = 0; r < rays.size(); r += lanes) {
      const int n = int(std::min<size_t>(lanes, rays.size() - r));
      ddaPacketOfWidth(lanes, g, grid.pe_of_voxel.data(), rays.data() + r, n, packet.data(), stride,
                       found);
      for (int k = 0; k < n; ++k) {
        entries.insert(entries.end(), packet.begin() + size_t(k) * stride,
                       packet.begin() + size_t(k) * stride + found[k]);
        begin.push_back(int(entries.size()));
      }
    }
    TraversalLists lists;
    lists.assign(begin, entries);
    expectListsMatchTheWalk(grid, rays.data(), rays.size(), lists);
  }
  EXPECT_TRUE(ddaPacketWidthIsBuilt(1));
  EXPECT_TRUE(ddaPacketWidthIsBuilt(ddaPacketLanes()));
  EXPECT_GE(widths, 1);
}

}  // namespace
}  // namespace gridrt
