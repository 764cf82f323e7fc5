#include "default_scene.h"

#include <cmath>

namespace gridrt {
namespace shapes {
namespace {

void addTriangle(Scene& scene, glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 na, glm::vec3 nb,
                 glm::vec3 nc, int material) {
  scene.positions.insert(scene.positions.end(), {a, b, c});
  scene.normals.insert(scene.normals.end(), {na, nb, nc});
  scene.material_of.push_back(material);
}

// Unit direction of the UV-sphere vertex on ring i (0 = north pole) and slice j. The poles
// are exact, and slice `segments` is slice 0 again, so the mesh closes without cracks.
glm::vec3 sphereDirection(int i, int j, int segments, int rings) {
  if (i == 0) return {0.0f, 1.0f, 0.0f};
  if (i == rings) return {0.0f, -1.0f, 0.0f};
  const double kPi = 3.14159265358979323846;
  double theta = kPi * i / rings;
  double phi = 2.0 * kPi * (j % segments) / segments;
  glm::dvec3 d(std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi));
  return glm::vec3(glm::normalize(d));
}

}  // namespace

int addMaterial(Scene& scene, const Material& material) {
  scene.materials.push_back(material);
  return static_cast<int>(scene.materials.size()) - 1;
}

void addRect(Scene& scene, glm::vec3 centre, glm::vec3 u, glm::vec3 v, int material) {
  glm::vec3 p0 = centre - u - v, p1 = centre + u - v, p2 = centre + u + v, p3 = centre - u + v;
  glm::vec3 n = glm::normalize(glm::cross(u, v));
  addTriangle(scene, p0, p1, p2, n, n, n, material);
  addTriangle(scene, p0, p2, p3, n, n, n, material);
}

void addBox(Scene& scene, glm::vec3 centre, glm::vec3 half_extents, float yaw_radians,
            int material) {
  float c = std::cos(yaw_radians), s = std::sin(yaw_radians);
  glm::vec3 x = glm::vec3(c, 0.0f, -s) * half_extents.x;
  glm::vec3 y = glm::vec3(0.0f, 1.0f, 0.0f) * half_extents.y;
  glm::vec3 z = glm::vec3(s, 0.0f, c) * half_extents.z;
  // Each face: (u, v) ordered so that cross(u, v) points out of the box.
  addRect(scene, centre + x, y, z, material);
  addRect(scene, centre - x, z, y, material);
  addRect(scene, centre + y, z, x, material);
  addRect(scene, centre - y, x, z, material);
  addRect(scene, centre + z, x, y, material);
  addRect(scene, centre - z, y, x, material);
}

void addSphere(Scene& scene, glm::vec3 centre, float radius, int segments, int rings,
               int material) {
  for (int i = 0; i < rings; ++i) {
    for (int j = 0; j < segments; ++j) {
      // a (i, j) -> b one ring south, d one slice east, c both. a, d, c, b winds
      // counter-clockwise seen from outside.
      glm::vec3 na = sphereDirection(i, j, segments, rings);
      glm::vec3 nb = sphereDirection(i + 1, j, segments, rings);
      glm::vec3 nc = sphereDirection(i + 1, j + 1, segments, rings);
      glm::vec3 nd = sphereDirection(i, j + 1, segments, rings);
      glm::vec3 a = centre + radius * na, b = centre + radius * nb;
      glm::vec3 c = centre + radius * nc, d = centre + radius * nd;
      if (i != 0) addTriangle(scene, a, d, c, na, nd, nc, material);
      if (i + 1 != rings) addTriangle(scene, a, c, b, na, nc, nb, material);
    }
  }
}

glm::mat4 lookAtWorld(glm::vec3 eye, glm::vec3 target, glm::vec3 up) {
  // v / |v| rather than glm::normalize (v * inversesqrt): axis-aligned vectors stay exact.
  auto unit = [](glm::vec3 v) { return v / glm::length(v); };
  glm::vec3 back = unit(eye - target);  // the camera looks down its local -Z
  glm::vec3 right = unit(glm::cross(up, back));
  glm::vec3 true_up = glm::cross(back, right);
  glm::mat4 world(1.0f);
  world[0] = glm::vec4(right, 0.0f);
  world[1] = glm::vec4(true_up, 0.0f);
  world[2] = glm::vec4(back, 0.0f);
  world[3] = glm::vec4(eye, 1.0f);
  return world;
}

}  // namespace shapes

namespace {

Material diffuse(const char* name, glm::vec3 albedo, float roughness) {
  Material m;
  m.name = name;
  m.base_color = albedo;
  m.metallic = 0.0f;
  m.roughness = roughness;
  m.double_sided = true;
  return m;
}

Material mirror() {
  Material m = diffuse("mirror", glm::vec3(0.95f), 0.0f);
  m.metallic = 1.0f;
  return m;
}

Material glass() {
  Material m = diffuse("glass", glm::vec3(1.0f), 0.0f);
  m.transmission = 1.0f;
  m.ior = 1.5f;
  return m;
}

// How far each wall of the room reaches past the seams where it meets its neighbours
// (metres), behind them and out of sight. Moeller-Trumbore is not watertight: a ray along
// an edge shared by two walls could miss both, and 20 pixels of a 640x480 render saw
// the background through the seams (DefaultScene.RaysAimedAtTheSeamsOfTheRoomHitAWall).
// The open side z = 0 stays flush with the opening.
constexpr float kSeamOverlap = 0.01f;

// About 2.2k triangles per sphere: 7.5 degree facets, smooth enough behind smooth normals.
constexpr int kSphereSegments = 48;
constexpr int kSphereRings = 24;

// Irradiance (lux) the point light gives the floor right below it. With Lambert shading
// (albedo / pi) the white floor there has radiance 0.75 * 3 / pi ~ 0.72, leaving headroom
// for the ceiling close above the light and the Phong highlights.
constexpr float kFloorIrradiance = 3.0f;

}  // namespace

Scene makeDefaultScene() {
  using namespace shapes;
  const float w = DefaultBox::kHalfWidth, h = DefaultBox::kHeight, d = DefaultBox::kDepth;
  const glm::vec3 X(1, 0, 0), Y(0, 1, 0), Z(0, 0, 1);
  Scene scene;

  // The room: normals point inwards; the side z = 0 is left open for the camera. Each wall
  // reaches kSeamOverlap past its seams (x beyond +-w, y beyond 0 and h, z beyond -d).
  const float o = kSeamOverlap;
  const float wide = w + o, tall = h / 2 + o, deep = (d + o) / 2, mid_z = -(d + o) / 2;
  int white = addMaterial(scene, diffuse("white", glm::vec3(0.75f), 0.9f));
  addRect(scene, {0, 0, mid_z}, Z * deep, X * wide, white);   // floor
  addRect(scene, {0, h, mid_z}, X * wide, Z * deep, white);   // ceiling
  addRect(scene, {0, h / 2, -d}, X * wide, Y * tall, white);  // back wall
  int red = addMaterial(scene, diffuse("red", {0.63f, 0.065f, 0.05f}, 0.9f));
  addRect(scene, {-w, h / 2, mid_z}, Y * tall, Z * deep, red);  // left wall
  int green = addMaterial(scene, diffuse("green", {0.14f, 0.45f, 0.091f}, 0.9f));
  addRect(scene, {w, h / 2, mid_z}, Z * deep, Y * tall, green);  // right wall

  // The objects, all in the back half of the box where the camera sees the floor: a tall
  // diffuse block at the back right, a mirror sphere at the back left and a glass sphere in
  // front of the block, so it refracts the block and the green wall.
  int block = addMaterial(scene, diffuse("block", {0.8f, 0.7f, 0.3f}, 0.6f));
  addBox(scene, {0.42f, 0.5f, -1.55f}, {0.22f, 0.5f, 0.22f}, 0.35f, block);
  int chrome = addMaterial(scene, mirror());
  addSphere(scene, {-0.42f, 0.33f, -1.45f}, 0.33f, kSphereSegments, kSphereRings, chrome);
  int crystal = addMaterial(scene, glass());
  addSphere(scene, {0.35f, 0.27f, -0.95f}, 0.27f, kSphereSegments, kSphereRings, crystal);

  Light light;
  light.type = LightType::Point;
  light.position = {0.0f, 0.85f * h, -d / 2};
  light.intensity = kFloorIrradiance * light.position.y * light.position.y;  // E * r^2
  scene.lights.push_back(light);
  scene.has_lights = true;

  // In front of the opening, on its axis, near enough that the opening fills the 4:3 frame
  // (every primary ray enters the box), looking at the box centre.
  scene.camera.name = "default camera";
  scene.camera.yfov = 0.6981317f;  // 40 degrees
  scene.camera.aspect = 4.0f / 3.0f;
  scene.camera.world = lookAtWorld({0.0f, h / 2, 2.0f}, {0.0f, h / 2, -d / 2});
  scene.has_camera = true;
  return scene;
}

}  // namespace gridrt
