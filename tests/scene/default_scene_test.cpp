// The built-in default scene (a Cornell-like box showing shadows, reflection and
// refraction) and the glTF writer, checked by brute-force CPU ray casting and by
// round trips through the loader.
#include "default_scene.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <string>
#include <vector>

#include "errors.h"
#include "gltf_loader.h"
#include "gltf_writer.h"
#include "moller_trumbore.h"
#include "test_support.h"

namespace fs = std::filesystem;
using gridrt::DefaultBox;
using gridrt::Light;
using gridrt::LightType;
using gridrt::Material;
using gridrt::Scene;

namespace {

const glm::vec3 kBoxCentre(0.0f, DefaultBox::kHeight / 2, -DefaultBox::kDepth / 2);
const glm::vec3 kBoxMin(-DefaultBox::kHalfWidth, 0.0f, -DefaultBox::kDepth);
const glm::vec3 kBoxMax(DefaultBox::kHalfWidth, DefaultBox::kHeight, 0.0f);
// Hits closer than this to a ray's origin are ignored (origins here lie on no surface, so
// this only guards against a degenerate t = 0). Scene scale is metres, about 2 m.
constexpr float kTMin = 1e-4f;
// Slack for "inside the box" checks: hit points lie on the walls up to float rounding.
constexpr float kWallSlack = 1e-4f;

struct Hit {
  bool found = false;
  float t = std::numeric_limits<float>::infinity();
  size_t triangle = 0;
};

// Closest hit over every triangle (the shared Moeller-Trumbore test, lowest index on ties).
Hit closestHit(const Scene& scene, glm::vec3 o, glm::vec3 d) {
  Hit hit;
  for (size_t t = 0; t < scene.triangleCount(); ++t) {
    glm::vec3 v0 = scene.positions[3 * t];
    glm::vec3 e1 = scene.positions[3 * t + 1] - v0, e2 = scene.positions[3 * t + 2] - v0;
    float th, u, v;
    if (gr_intersect_mt(o.x, o.y, o.z, d.x, d.y, d.z, v0.x, v0.y, v0.z, e1.x, e1.y, e1.z, e2.x,
                        e2.y, e2.z, &th, &u, &v) &&
        th > kTMin && th < hit.t) {
      hit.found = true;
      hit.t = th;
      hit.triangle = t;
    }
  }
  return hit;
}

glm::vec3 geometricNormal(const Scene& scene, size_t t) {
  const glm::vec3* p = &scene.positions[3 * t];
  return glm::normalize(glm::cross(p[1] - p[0], p[2] - p[0]));
}

// n directions spread evenly over the unit sphere (Fibonacci lattice), deterministic.
std::vector<glm::vec3> sphereDirections(int n) {
  std::vector<glm::vec3> out;
  const double kGolden = 2.399963229728653;  // pi * (3 - sqrt 5)
  for (int i = 0; i < n; ++i) {
    double y = 1.0 - (i + 0.5) * 2.0 / n;
    double r = std::sqrt(1.0 - y * y);
    out.emplace_back(r * std::cos(kGolden * i), y, r * std::sin(kGolden * i));
  }
  return out;
}

// Does a ray from the box centre leave through the open side z = 0 (with a margin)?
bool leavesThroughOpening(glm::vec3 d, float margin) {
  if (d.z <= 0.0f) return false;
  glm::vec3 p = kBoxCentre + d * (-kBoxCentre.z / d.z);
  return std::abs(p.x) < DefaultBox::kHalfWidth - margin && p.y > margin &&
         p.y < DefaultBox::kHeight - margin;
}

bool insideBox(glm::vec3 p, float slack) {
  return glm::all(glm::greaterThanEqual(p, kBoxMin - slack)) &&
         glm::all(glm::lessThanEqual(p, kBoxMax + slack));
}

// World direction of the primary ray through normalised image coordinates (-1..1, +y up).
glm::vec3 primaryDirection(const gridrt::Camera& camera, float sx, float sy) {
  float tan_half = std::tan(camera.yfov / 2);
  glm::vec3 local(sx * tan_half * camera.aspect, sy * tan_half, -1.0f);
  return glm::normalize(glm::mat3(camera.world) * local);
}

template <typename Predicate>
int findMaterial(const Scene& scene, Predicate predicate) {
  for (size_t m = 0; m < scene.materials.size(); ++m)
    if (predicate(scene.materials[m])) return static_cast<int>(m);
  return -1;
}

size_t trianglesWith(const Scene& scene, int material) {
  size_t n = 0;
  for (int m : scene.material_of) n += m == material;
  return n;
}

}  // namespace

TEST(DefaultScene, HasConsistentArraysAndStaysUnderTriangleBudget) {
  Scene scene = gridrt::makeDefaultScene();
  ASSERT_GT(scene.triangleCount(), 0u);
  EXPECT_LT(scene.triangleCount(), 10000u);
  EXPECT_EQ(scene.positions.size(), 3 * scene.triangleCount());
  EXPECT_EQ(scene.normals.size(), scene.positions.size());
  ASSERT_EQ(scene.material_of.size(), scene.triangleCount());
  size_t runs = 1;
  for (size_t t = 0; t < scene.triangleCount(); ++t) {
    ASSERT_GE(scene.material_of[t], 0);
    ASSERT_LT(static_cast<size_t>(scene.material_of[t]), scene.materials.size());
    if (t > 0 && scene.material_of[t] != scene.material_of[t - 1]) ++runs;
  }
  EXPECT_EQ(runs, scene.materials.size()) << "triangles should come grouped by material";
  for (const Material& m : scene.materials) EXPECT_TRUE(m.double_sided) << m.name;
}

TEST(DefaultScene, IsDeterministic) {
  Scene a = gridrt::makeDefaultScene(), b = gridrt::makeDefaultScene();
  EXPECT_TRUE(a.positions == b.positions);
  EXPECT_TRUE(a.normals == b.normals);
  EXPECT_TRUE(a.material_of == b.material_of);
}

TEST(DefaultScene, HasMirrorGlassDiffuseAndColouredWallsInUse) {
  Scene scene = gridrt::makeDefaultScene();
  int mirror = findMaterial(scene, [](const Material& m) {
    return m.metallic == 1.0f && m.roughness == 0.0f && m.transmission == 0.0f &&
           glm::all(glm::greaterThan(m.base_color, glm::vec3(0.9f)));
  });
  int glass = findMaterial(scene, [](const Material& m) {
    return m.transmission == 1.0f && m.ior == 1.5f && m.roughness == 0.0f && m.metallic == 0.0f &&
           m.base_color == glm::vec3(1.0f);
  });
  int diffuse = findMaterial(scene, [](const Material& m) {
    return m.metallic == 0.0f && m.transmission == 0.0f && m.roughness > 0.0f &&
           m.base_color.r > m.base_color.b && m.base_color.g > m.base_color.b;  // yellowish
  });
  int red = findMaterial(scene, [](const Material& m) {
    return m.base_color.r > 0.5f && m.base_color.g < 0.1f && m.base_color.b < 0.1f;
  });
  int green = findMaterial(scene, [](const Material& m) {
    return m.base_color.g > 0.4f && m.base_color.r < 0.2f && m.base_color.b < 0.2f;
  });
  for (int m : {mirror, glass, diffuse, red, green}) {
    ASSERT_GE(m, 0);
    EXPECT_GT(trianglesWith(scene, m), 0u) << scene.materials[m].name;
  }
  // The spheres are tessellated finely enough to look round behind smooth normals.
  EXPECT_GE(trianglesWith(scene, mirror), 1000u);
  EXPECT_GE(trianglesWith(scene, glass), 1000u);
}

TEST(DefaultScene, NormalsAreUnitAndOnTheFrontSideOfTheirTriangle) {
  Scene scene = gridrt::makeDefaultScene();
  for (size_t t = 0; t < scene.triangleCount(); ++t) {
    glm::vec3 ng = geometricNormal(scene, t);
    for (int k = 0; k < 3; ++k) {
      glm::vec3 n = scene.normals[3 * t + k];
      ASSERT_NEAR(glm::length(n), 1.0f, 1e-6f) << "triangle " << t;
      // Smooth sphere normals tilt at most half a facet (3.75 degrees) from the face.
      ASSERT_GT(glm::dot(n, ng), 0.99f) << "triangle " << t;
    }
  }
}

TEST(DefaultScene, BoxIsClosedOnFiveSidesAndOpenTowardsTheCamera) {
  Scene scene = gridrt::makeDefaultScene();
  int closed = 0, open = 0;
  for (glm::vec3 d : sphereDirections(2000)) {
    Hit hit = closestHit(scene, kBoxCentre, d);
    if (leavesThroughOpening(d, 0.02f)) {
      ++open;
      if (hit.found) {  // an object in the box may stand in the way, nothing beyond it
        EXPECT_TRUE(insideBox(kBoxCentre + hit.t * d, kWallSlack));
      }
      continue;
    }
    if (!leavesThroughOpening(d, -0.02f)) {  // clearly towards a wall, floor or ceiling
      ++closed;
      ASSERT_TRUE(hit.found) << "ray " << d.x << " " << d.y << " " << d.z << " escapes";
      EXPECT_TRUE(insideBox(kBoxCentre + hit.t * d, kWallSlack));
    }
  }
  EXPECT_GT(closed, 1500);
  EXPECT_GT(open, 100);
  // Straight out of the opening nothing is in the way.
  EXPECT_FALSE(closestHit(scene, kBoxCentre + glm::vec3(0, 0.5f, 0), {0, 0, 1}).found);
}

// Rays from the camera aimed exactly at the seams where two walls of the room meet (the
// eight inner edges of the box). Moeller-Trumbore is not watertight: a ray along the
// shared edge of two walls may miss both, and the built-in scene rendered 20 background
// pixels along its seams at 640x480 before the walls overlapped there.
TEST(DefaultScene, RaysAimedAtTheSeamsOfTheRoomHitAWall) {
  Scene scene = gridrt::makeDefaultScene();
  const glm::vec3 eye(scene.camera.world[3]);
  const float w = DefaultBox::kHalfWidth, h = DefaultBox::kHeight, d = DefaultBox::kDepth;
  // Each seam from one corner to another, sampled between them.
  const glm::vec3 seams[8][2] = {
      {{-w, 0, -d}, {w, 0, -d}},  {{-w, h, -d}, {w, h, -d}},  // back wall with floor, ceiling
      {{-w, 0, -d}, {-w, h, -d}}, {{w, 0, -d}, {w, h, -d}},   // back wall with the side walls
      {{-w, 0, -d}, {-w, 0, 0}},  {{w, 0, -d}, {w, 0, 0}},    // floor with the side walls
      {{-w, h, -d}, {-w, h, 0}},  {{w, h, -d}, {w, h, 0}}};   // ceiling with the side walls
  int aimed = 0, leaks = 0;
  for (const auto& seam : seams)
    for (int k = 1; k < 4000; ++k) {
      const glm::vec3 target = seam[0] + (seam[1] - seam[0]) * (float(k) / 4000.0f);
      const glm::vec3 dir = glm::normalize(target - eye);
      if (dir.z >= 0.0f) continue;  // the seam's front end, level with the eye's z
      ++aimed;
      leaks += !closestHit(scene, eye, dir).found;
    }
  EXPECT_GT(aimed, 30000);
  EXPECT_EQ(leaks, 0);
}

TEST(DefaultScene, EverySurfaceSeenFromInsideFacesTheViewer) {
  // Walls wind counter-clockwise seen from the room, objects seen from outside: from any
  // point of free space the closest hit is a front face.
  Scene scene = gridrt::makeDefaultScene();
  for (glm::vec3 d : sphereDirections(1000)) {
    Hit hit = closestHit(scene, kBoxCentre, d);
    if (!hit.found) continue;
    EXPECT_LT(glm::dot(geometricNormal(scene, hit.triangle), d), 0.0f)
        << scene.materials[scene.material_of[hit.triangle]].name << " triangle " << hit.triangle;
  }
}

TEST(DefaultScene, PointLightInsideTheBoxGivesTheFloorAFewLux) {
  Scene scene = gridrt::makeDefaultScene();
  ASSERT_TRUE(scene.has_lights);
  ASSERT_EQ(scene.lights.size(), 1u);
  const Light& light = scene.lights[0];
  EXPECT_EQ(light.type, LightType::Point);
  EXPECT_TRUE(insideBox(light.position, -0.05f)) << "not well inside the box";
  EXPECT_GT(light.position.y, 0.8f * DefaultBox::kHeight) << "not near the ceiling";

  // The floor right below the light sees it unoccluded and gets E = I / d^2 in 3..5 lux,
  // so the white floor (albedo 0.75, Lambert) has a radiance near 1.
  glm::vec3 floor(light.position.x, 0.0f, light.position.z);
  glm::vec3 to_light = light.position - floor;
  Hit blocker = closestHit(scene, floor, glm::normalize(to_light));
  EXPECT_TRUE(!blocker.found || blocker.t > glm::length(to_light)) << "floor is in shadow";
  float irradiance = light.intensity / glm::dot(to_light, to_light);
  EXPECT_GE(irradiance, 3.0f);
  EXPECT_LE(irradiance, 5.0f);
}

TEST(DefaultScene, CameraLooksIntoTheOpeningAtTheBoxCentre) {
  Scene scene = gridrt::makeDefaultScene();
  ASSERT_TRUE(scene.has_camera);
  const gridrt::Camera& camera = scene.camera;
  EXPECT_FALSE(camera.orthographic);
  EXPECT_NEAR(camera.yfov, 0.6981317f, 1e-6f);
  EXPECT_NEAR(camera.aspect, 4.0f / 3.0f, 1e-6f);
  glm::mat3 rotation(camera.world);
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(glm::length(rotation[i]), 1.0f, 1e-6f);

  // In front of the opening, on the open side, within its outline.
  glm::vec3 eye(camera.world[3]);
  EXPECT_GE(eye.z, kBoxMax.z);
  EXPECT_LT(std::abs(eye.x), DefaultBox::kHalfWidth);
  EXPECT_GT(eye.y, 0.0f);
  EXPECT_LT(eye.y, DefaultBox::kHeight);

  // The box centre projects to the image centre.
  glm::vec3 local = glm::inverse(camera.world) * glm::vec4(kBoxCentre, 1.0f);
  ASSERT_LT(local.z, 0.0f) << "box centre behind the camera";
  float tan_half = std::tan(camera.yfov / 2);
  EXPECT_NEAR(local.x / -local.z / (tan_half * camera.aspect), 0.0f, 0.02f);
  EXPECT_NEAR(local.y / -local.z / tan_half, 0.0f, 0.02f);

  // The opening fills the frame: every primary ray meets the scene inside the box.
  for (int row = 0; row <= 24; ++row) {
    for (int column = 0; column <= 32; ++column) {
      glm::vec3 d = primaryDirection(camera, column / 16.0f - 1.0f, row / 12.0f - 1.0f);
      Hit hit = closestHit(scene, eye, d);
      ASSERT_TRUE(hit.found) << "pixel (" << column << ", " << row << ") sees the background";
      EXPECT_TRUE(insideBox(eye + hit.t * d, kWallSlack));
    }
  }
}

// ---- glTF writer -------------------------------------------------------------------

namespace {

void expectSameMaterial(const Material& got, const Material& want, const std::string& where) {
  EXPECT_EQ(got.name, want.name) << where;
  for (int c = 0; c < 3; ++c) {
    EXPECT_FLOAT_EQ(got.base_color[c], want.base_color[c]) << where;
    EXPECT_FLOAT_EQ(got.emissive[c], want.emissive[c]) << where;
  }
  EXPECT_FLOAT_EQ(got.metallic, want.metallic) << where;
  EXPECT_FLOAT_EQ(got.roughness, want.roughness) << where;
  EXPECT_FLOAT_EQ(got.transmission, want.transmission) << where;
  EXPECT_FLOAT_EQ(got.ior, want.ior) << where;
  EXPECT_FLOAT_EQ(got.attenuation_distance, want.attenuation_distance) << where;
  if (want.attenuation_distance > 0.0f) {
    for (int c = 0; c < 3; ++c)
      EXPECT_FLOAT_EQ(got.attenuation_color[c], want.attenuation_color[c]) << where;
  }
  EXPECT_EQ(got.double_sided, want.double_sided) << where;
}

void expectNear(glm::vec3 got, glm::vec3 want, float tolerance, const std::string& where) {
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(got[c], want[c], tolerance) << where << " [" << c << "]";
}

// What the loader reads back is the written scene: same triangles in the same order
// (positions bit for bit unless a tolerance is given), same material per triangle, same
// lights and camera.
void expectRoundTrip(const Scene& written, const Scene& read, float position_tolerance = 0.0f) {
  ASSERT_EQ(read.triangleCount(), written.triangleCount());
  if (position_tolerance == 0.0f) {
    EXPECT_TRUE(read.positions == written.positions) << "positions differ";
  } else {
    for (size_t i = 0; i < written.positions.size(); ++i)
      expectNear(read.positions[i], written.positions[i], position_tolerance,
                 "position " + std::to_string(i));
  }
  ASSERT_EQ(read.normals.size(), written.normals.size());
  for (size_t i = 0; i < written.normals.size(); ++i)
    expectNear(read.normals[i], written.normals[i], 1e-6f, "normal " + std::to_string(i));
  ASSERT_EQ(read.material_of.size(), written.material_of.size());
  for (size_t t = 0; t < written.triangleCount(); ++t) {
    ASSERT_EQ(read.material_of[t], written.material_of[t]) << "triangle " << t;
  }
  ASSERT_EQ(read.materials.size(), written.materials.size());
  for (size_t m = 0; m < written.materials.size(); ++m)
    expectSameMaterial(read.materials[m], written.materials[m], "material " + std::to_string(m));

  EXPECT_EQ(read.has_lights, written.has_lights);
  ASSERT_EQ(read.lights.size(), written.lights.size());
  for (size_t i = 0; i < written.lights.size(); ++i) {
    const Light &got = read.lights[i], &want = written.lights[i];
    std::string where = "light " + std::to_string(i);
    EXPECT_EQ(got.type, want.type) << where;
    EXPECT_FLOAT_EQ(got.intensity, want.intensity) << where;
    expectNear(got.color, want.color, 1e-6f, where);
    EXPECT_FLOAT_EQ(got.range, want.range) << where;
    if (want.type != LightType::Directional) expectNear(got.position, want.position, 1e-6f, where);
    if (want.type != LightType::Point)
      expectNear(got.direction, glm::normalize(want.direction), 1e-6f, where);
    if (want.type == LightType::Spot) {
      EXPECT_FLOAT_EQ(got.inner_cone, want.inner_cone) << where;
      EXPECT_FLOAT_EQ(got.outer_cone, want.outer_cone) << where;
    }
  }

  EXPECT_EQ(read.has_camera, written.has_camera);
  if (written.has_camera) {
    const gridrt::Camera &got = read.camera, &want = written.camera;
    EXPECT_EQ(got.orthographic, want.orthographic);
    if (want.orthographic) {
      EXPECT_FLOAT_EQ(got.xmag, want.xmag);
      EXPECT_FLOAT_EQ(got.ymag, want.ymag);
    } else {
      EXPECT_FLOAT_EQ(got.yfov, want.yfov);
      EXPECT_FLOAT_EQ(got.aspect, want.aspect);
    }
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 4; ++r)
        EXPECT_NEAR(got.world[c][r], want.world[c][r], 1e-6f) << "camera world " << c << r;
  }
}

std::string readFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

// An empty directory of its own for each test.
std::string freshDir(const std::string& name) {
  std::string dir = gridrt::test::tempPath("default_scene_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

// Four quads whose materials interleave, every material extension, every light kind and an
// orthographic camera.
Scene featureScene() {
  using namespace gridrt::shapes;
  Scene scene;
  Material glow;
  glow.name = "glow";
  glow.base_color = {0.2f, 0.3f, 0.4f};
  glow.emissive = {2.0f, 4.0f, 1.0f};  // beyond emissiveFactor's [0, 1]: needs a strength
  Material tinted;
  tinted.name = "tinted glass";
  tinted.transmission = 0.5f;
  tinted.ior = 1.33f;
  tinted.attenuation_color = {0.9f, 0.5f, 0.25f};
  tinted.attenuation_distance = 0.75f;
  tinted.double_sided = false;
  int a = addMaterial(scene, glow), b = addMaterial(scene, tinted);
  glm::vec3 x(1, 0, 0), y(0, 1, 0), z(0, 0, 1);
  addRect(scene, {0, 0, 0}, x, y, a);
  addRect(scene, {0, 0, -1}, x, y, b);
  addRect(scene, {0, 0, -2}, y, z, a);  // a again: the global order must survive
  addRect(scene, {0, 0, -3}, z, x, b);

  Light spot;
  spot.type = LightType::Spot;
  spot.position = {1.0f, 2.0f, 3.0f};
  spot.direction = glm::normalize(glm::vec3(-1.0f, -2.0f, -0.5f));
  spot.color = {1.0f, 0.5f, 0.25f};
  spot.intensity = 12.5f;
  spot.inner_cone = 0.2f;
  spot.outer_cone = 0.6f;
  spot.range = 20.0f;
  Light sun;
  sun.type = LightType::Directional;
  sun.direction = {0.0f, -1.0f, 0.0f};  // straight down: the basis needs another up
  sun.intensity = 3.0f;
  Light bulb;
  bulb.position = {-0.5f, 0.25f, 0.125f};
  bulb.intensity = 7.0f;
  scene.lights = {spot, sun, bulb};
  scene.has_lights = true;

  scene.camera.name = "ortho";
  scene.camera.orthographic = true;
  scene.camera.xmag = 2.0f;
  scene.camera.ymag = 1.5f;
  scene.camera.world = lookAtWorld({3, 4, 5}, {0, 0, -1});
  scene.has_camera = true;
  return scene;
}

}  // namespace

TEST(GltfWriter, DefaultSceneRoundTripsThroughGltf) {
  Scene scene = gridrt::makeDefaultScene();
  std::string path = freshDir("gltf") + "/default.gltf";
  gridrt::writeGltf(scene, path);
  std::string text = readFile(path);
  ASSERT_FALSE(text.empty());
  EXPECT_EQ(text[0], '{');
  EXPECT_NE(text.find("data:application/octet-stream;base64,"), std::string::npos);
  for (const char* ext :
       {"KHR_lights_punctual", "KHR_materials_transmission", "KHR_materials_volume"})
    EXPECT_NE(text.find(ext), std::string::npos) << ext;
  expectRoundTrip(scene, gridrt::loadGltfFile(path));
}

TEST(GltfWriter, DefaultSceneRoundTripsThroughGlb) {
  Scene scene = gridrt::makeDefaultScene();
  std::string path = freshDir("glb") + "/default.GLB";  // the extension's case is ignored
  gridrt::writeGltf(scene, path);
  EXPECT_EQ(readFile(path).substr(0, 4), "glTF");
  expectRoundTrip(scene, gridrt::loadGltfFile(path));
}

TEST(GltfWriter, EveryMaterialLightAndCameraFeatureRoundTrips) {
  Scene scene = featureScene();
  std::string dir = freshDir("features");
  for (const char* name : {"features.gltf", "features.glb"}) {
    SCOPED_TRACE(name);
    gridrt::writeGltf(scene, dir + "/" + name);
    expectRoundTrip(scene, gridrt::loadGltfFile(dir + "/" + name));
  }
  std::string text = readFile(dir + "/features.gltf");
  for (const char* ext : {"KHR_materials_emissive_strength", "KHR_materials_ior",
                          "KHR_materials_volume", "KHR_materials_transmission"})
    EXPECT_NE(text.find(ext), std::string::npos) << ext;
}

TEST(GltfWriter, SceneWithoutNormalsOrCameraRoundTrips) {
  Scene scene = featureScene();
  scene.normals.clear();
  scene.has_camera = false;
  scene.lights.clear();
  scene.has_lights = false;
  std::string path = freshDir("bare") + "/bare.gltf";
  gridrt::writeGltf(scene, path);
  Scene read = gridrt::loadGltfFile(path);
  expectRoundTrip(scene, read);
}

TEST(GltfWriter, FailedWriteThrowsAndLeavesNoFileBehind) {
  Scene scene = gridrt::makeDefaultScene();
  std::string dir = freshDir("fail");
  // The target's folder does not exist.
  EXPECT_THROW(gridrt::writeGltf(scene, dir + "/missing/out.gltf"), gridrt::RenderError);
  // The target is a folder: the temporary file is written, but cannot replace it.
  fs::create_directories(dir + "/taken.gltf");
  try {
    gridrt::writeGltf(scene, dir + "/taken.gltf");
    ADD_FAILURE() << "no exception";
  } catch (const gridrt::RenderError& e) {
    std::string message = e.what();
    EXPECT_NE(message.find("taken.gltf"), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
  std::vector<std::string> left;
  for (const auto& entry : fs::directory_iterator(dir)) left.push_back(entry.path().filename());
  EXPECT_EQ(left, std::vector<std::string>{"taken.gltf"});
  EXPECT_TRUE(fs::is_directory(dir + "/taken.gltf"));
}

TEST(GltfWriter, InconsistentSceneIsRejected) {
  Scene scene = featureScene();
  scene.material_of[1] = 7;
  EXPECT_THROW(gridrt::writeGltf(scene, freshDir("bad") + "/bad.gltf"), gridrt::SceneError);
}

TEST(CommittedScenes, DefaultGltfMatchesTheBuiltInScene) {
  // scenes/default.gltf is regenerated by tools/make_scenes (scenes/README.md). Another
  // libm may round the sphere's sines differently by an ulp, hence the tolerance.
  std::string path = gridrt::test::sourcePath("scenes/default.gltf");
  ASSERT_TRUE(fs::exists(path)) << path;
  expectRoundTrip(gridrt::makeDefaultScene(), gridrt::loadGltfFile(path), 1e-6f);
}

TEST(CommittedScenes, EveryTestSceneLoadsWithCameraAndLights) {
  for (const char* name : {"quad_light.gltf", "refraction_slab.gltf", "mirror_test.gltf"}) {
    Scene scene = gridrt::loadGltfFile(gridrt::test::sourcePath(std::string("scenes/") + name));
    EXPECT_GT(scene.triangleCount(), 0u) << name;
    EXPECT_TRUE(scene.has_camera) << name;
    EXPECT_TRUE(scene.has_lights) << name;
  }
}
