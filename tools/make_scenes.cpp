// make_scenes OUTDIR: writes the committed test scenes (scenes/README.md) as glTF:
//   default.gltf          the built-in default scene (host/scene/default_scene.cpp)
//   quad_light.gltf       a grey quad under a point light: pixels follow Lambert exactly
//   refraction_slab.gltf  a turned glass slab in front of a checkered wall
//   mirror_test.gltf      a 45-degree mirror showing an emissive red wall to the camera
#include <cmath>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <string>

#include "default_scene.h"
#include "errors.h"
#include "gltf_writer.h"

namespace {

using gridrt::Material;
using gridrt::Scene;
using namespace gridrt::shapes;

const glm::vec3 kX(1, 0, 0), kY(0, 1, 0), kZ(0, 0, 1);
constexpr float kYFov40 = 0.6981317f;

Material material(const char* name, glm::vec3 base_color, float metallic, float roughness) {
  Material m;
  m.name = name;
  m.base_color = base_color;
  m.metallic = metallic;
  m.roughness = roughness;
  return m;
}

void addPointLight(Scene& scene, glm::vec3 position, float intensity_cd) {
  gridrt::Light light;
  light.type = gridrt::LightType::Point;
  light.position = position;
  light.intensity = intensity_cd;
  scene.lights.push_back(light);
  scene.has_lights = true;
}

void setCamera(Scene& scene, const char* name, glm::vec3 eye, glm::vec3 target, glm::vec3 up) {
  scene.camera.name = name;
  scene.camera.yfov = kYFov40;
  scene.camera.aspect = 4.0f / 3.0f;
  scene.camera.world = lookAtWorld(eye, target, up);
  scene.has_camera = true;
}

// A 2 x 2 m quad in the plane y = 0 facing +Y, albedo 0.5, a 1 cd point light 1 m above its
// centre and the camera 2 m above looking straight down (image up = -Z): the quad fills the
// frame, and a pixel seeing point p has radiance 0.5 / pi * cos(theta) / d^2 from the light.
Scene quadLight() {
  Scene scene;
  int grey = addMaterial(scene, material("grey", glm::vec3(0.5f), 0.0f, 1.0f));
  addRect(scene, {0, 0, 0}, kZ, kX, grey);
  addPointLight(scene, {0, 1, 0}, 1.0f);
  setCamera(scene, "top camera", {0, 2, 0}, {0, 0, 0}, -kZ);
  return scene;
}

// A glass slab (ior 1.5, 0.8 x 0.8 x 0.2 m) turned 30 degrees about +Y, 1 m in front of a
// checkered wall (8 x 6 squares of 0.3 m), so the checker seen through it is displaced.
Scene refractionSlab() {
  Scene scene;
  const int kColumns = 8, kRows = 6;
  const float kSquare = 0.3f;
  int light = addMaterial(scene, material("checker light", glm::vec3(0.8f), 0.0f, 0.9f));
  int dark = addMaterial(scene, material("checker dark", {0.1f, 0.2f, 0.7f}, 0.0f, 0.9f));
  for (int colour : {light, dark}) {  // one run of triangles per material
    for (int row = 0; row < kRows; ++row) {
      for (int column = 0; column < kColumns; ++column) {
        if (((row + column) % 2 == 0) != (colour == light)) continue;
        glm::vec3 centre((column - (kColumns - 1) / 2.0f) * kSquare,
                         (row - (kRows - 1) / 2.0f) * kSquare, -1.0f);
        addRect(scene, centre, kX * (kSquare / 2), kY * (kSquare / 2), colour);  // faces +Z
      }
    }
  }
  Material glass = material("glass", glm::vec3(1.0f), 0.0f, 0.0f);
  glass.transmission = 1.0f;
  glass.ior = 1.5f;
  addBox(scene, {0, 0, 0}, {0.4f, 0.4f, 0.1f}, 0.5235988f, addMaterial(scene, glass));
  addPointLight(scene, {-0.8f, 0.8f, 0.5f}, 16.0f);  // about 3.6 lux on the wall centre
  setCamera(scene, "front camera", {0, 0, 1.4f}, {0, 0, -1}, kY);  // the wall fills the frame
  return scene;
}

// A perfect mirror (metallic 1, roughness 0, white) at the origin facing (1, 0, 1)/sqrt 2
// turns the camera's view (down -Z from z = 3) towards +X, where a red wall that only emits
// (albedo 0, emissive (1, 0, 0)) stands at x = 2.5 out of the camera's direct view: the
// mirror's pixels are pure red whatever the lighting.
Scene mirrorTest() {
  Scene scene;
  glm::vec3 tangent = glm::normalize(glm::vec3(1, 0, -1));
  int mirror = addMaterial(scene, material("mirror", glm::vec3(1.0f), 1.0f, 0.0f));
  addRect(scene, {0, 0, 0}, tangent * 0.6f, kY * 0.4f, mirror);  // faces (1, 0, 1)
  Material red = material("red emitter", glm::vec3(0.0f), 0.0f, 1.0f);
  red.emissive = {1.0f, 0.0f, 0.0f};
  addRect(scene, {2.5f, 0, 0}, kZ * 1.2f, kY * 1.2f, addMaterial(scene, red));  // faces -X
  addPointLight(scene, {0, 2, 2}, 4.0f);
  setCamera(scene, "front camera", {0, 0, 3}, {0, 0, 0}, kY);
  return scene;
}

void write(const Scene& scene, const std::filesystem::path& path) {
  gridrt::writeGltf(scene, path.string());
  std::printf("%s: %zu triangles, %ju bytes\n", path.string().c_str(), scene.triangleCount(),
              static_cast<uintmax_t>(std::filesystem::file_size(path)));
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: make_scenes OUTDIR\n");
    return 2;
  }
  try {
    std::filesystem::path dir(argv[1]);
    std::filesystem::create_directories(dir);
    write(gridrt::makeDefaultScene(), dir / "default.gltf");
    write(quadLight(), dir / "quad_light.gltf");
    write(refractionSlab(), dir / "refraction_slab.gltf");
    write(mirrorTest(), dir / "mirror_test.gltf");
  } catch (const std::exception& e) {
    std::fprintf(stderr, "make_scenes: %s\n", e.what());
    return 1;
  }
  return 0;
}
