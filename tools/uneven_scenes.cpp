#include "uneven_scenes.h"

#include <algorithm>

#include "default_scene.h"

namespace gridrt {

using namespace shapes;

namespace {

struct Box {
  glm::vec3 lo{1e30f}, hi{-1e30f};
  glm::vec3 centre() const { return 0.5f * (lo + hi); }
  float size() const {
    glm::vec3 d = hi - lo;
    return std::max(d.x, std::max(d.y, d.z));
  }
};

Box boxOf(const Scene& s) {
  Box b;
  for (const glm::vec3& p : s.positions) {
    b.lo = glm::min(b.lo, p);
    b.hi = glm::max(b.hi, p);
  }
  return b;
}

// The model's triangles moved by `offset`, with its materials appended once to `scene`
// (material_base: where they start, -1 to append them now).
void addModel(Scene& scene, const Scene& model, glm::vec3 offset, int& material_base) {
  if (material_base < 0) {
    material_base = int(scene.materials.size());
    for (const Material& m : model.materials) scene.materials.push_back(m);
  }
  const bool normals = !model.normals.empty();
  for (size_t t = 0; t < model.triangleCount(); ++t) {
    for (int k = 0; k < 3; ++k) {
      scene.positions.push_back(model.positions[3 * t + k] + offset);
      glm::vec3 n = normals ? model.normals[3 * t + k] : glm::vec3(0, 1, 0);
      scene.normals.push_back(n);
    }
    scene.material_of.push_back(material_base + model.material_of[t]);
  }
}

Material grey(const char* name) {
  Material m;
  m.name = name;
  m.base_color = glm::vec3(0.6f);
  m.roughness = 0.9f;
  return m;
}

void finish(Scene& scene, glm::vec3 eye, glm::vec3 target, glm::vec3 light, float intensity) {
  Light l;
  l.type = LightType::Point;
  l.position = light;
  l.intensity = intensity;
  scene.lights.push_back(l);
  scene.has_lights = true;
  scene.camera.name = "camera";
  scene.camera.yfov = 0.6981317f;
  scene.camera.aspect = 4.0f / 3.0f;
  scene.camera.world = lookAtWorld(eye, target);
  scene.has_camera = true;
}

}  // namespace

// The model on a square floor `scale` times its size at its lowest point, centred below it;
// the camera 1.6 sizes from the model's centre, a little above it, looking at it.
Scene floorScene(const Scene& model, float scale) {
  const Box b = boxOf(model);
  const float s = b.size(), half = 0.5f * scale * s;
  const glm::vec3 c = b.centre();
  Scene scene;
  int base = -1;
  addModel(scene, model, glm::vec3(0.0f), base);
  const int floor = addMaterial(scene, grey("floor"));
  // Faces +Y: cross(u, v) with u = +Z, v = +X.
  addRect(scene, {c.x, b.lo.y, c.z}, {0, 0, half}, {half, 0, 0}, floor);
  finish(scene, c + glm::vec3(0.9f, 0.45f, 1.2f) * s, c, c + glm::vec3(0.5f, 2.0f, 1.0f) * s,
         4.0f * s * s);
  return scene;
}

// Eight copies at the corners of a cube `spread` times the model's size; the camera beside
// the first, looking past it towards the cube's centre.
Scene scatteredScene(const Scene& model, float spread) {
  const Box b = boxOf(model);
  const float s = b.size(), d = spread * s;
  Scene scene;
  int base = -1;
  for (int k = 0; k < 8; ++k)
    addModel(scene, model, glm::vec3(k & 1 ? d : 0, k & 2 ? d : 0, k & 4 ? d : 0) - b.centre(),
             base);
  const glm::vec3 centre(0.5f * d);
  finish(scene, glm::vec3(-1.2f * s, -0.4f * s, -1.4f * s), centre, centre, 4.0f * d * d);
  return scene;
}

// `count` copies in a row along +X, 1.5 sizes apart; the camera at the row's start, off to
// the side, looking along it.
Scene rowScene(const Scene& model, int count) {
  const Box b = boxOf(model);
  const float s = b.size(), step = 1.5f * s;
  Scene scene;
  int base = -1;
  for (int k = 0; k < count; ++k)
    addModel(scene, model, glm::vec3(k * step, 0, 0) - b.centre(), base);
  finish(scene, glm::vec3(-1.5f * s, 0.5f * s, 1.5f * s), glm::vec3(0.25f * count * step, 0, 0),
         glm::vec3(0.5f * count * step, 3.0f * s, 3.0f * s), 4.0f * count * count * step * step);
  return scene;
}

// The model and one triangle `scale` times its size through its centre, tilted.
Scene hugeTriangleScene(const Scene& model, float scale) {
  const Box b = boxOf(model);
  const float s = b.size(), r = scale * s;
  const glm::vec3 c = b.centre();
  Scene scene;
  int base = -1;
  addModel(scene, model, glm::vec3(0.0f), base);
  const int m = addMaterial(scene, grey("huge triangle"));
  const glm::vec3 u = glm::normalize(glm::vec3(1.0f, 0.3f, 0.2f)),
                  v = glm::normalize(glm::cross(u, glm::vec3(0.1f, 0.2f, 1.0f)));
  const glm::vec3 p0 = c + r * u, p1 = c + r * (-0.5f * u + 0.866f * v),
                  p2 = c + r * (-0.5f * u - 0.866f * v);
  const glm::vec3 n = glm::normalize(glm::cross(p1 - p0, p2 - p0));
  for (const glm::vec3& p : {p0, p1, p2}) {
    scene.positions.push_back(p);
    scene.normals.push_back(n);
  }
  scene.material_of.push_back(m);
  finish(scene, c + glm::vec3(0.9f, 0.45f, 1.2f) * s, c, c + glm::vec3(0.5f, 2.0f, 1.0f) * s,
         4.0f * s * s);
  return scene;
}

std::vector<std::pair<std::string, Scene>> unevenScenes(const Scene& model, int row_count) {
  std::vector<std::pair<std::string, Scene>> scenes;
  for (int scale : {1, 10, 100, 1000})
    scenes.emplace_back("floor_" + std::to_string(scale) + "x", floorScene(model, float(scale)));
  scenes.emplace_back("scattered", scatteredScene(model, 60.0f));
  scenes.emplace_back("row", rowScene(model, row_count));
  scenes.emplace_back("huge_triangle", hugeTriangleScene(model, 100.0f));
  return scenes;
}

}  // namespace gridrt
