// The scene as the renderer sees it: world-space triangles in global load order, their
// materials, the lights and the camera. Loaders (glTF, the built-in default scene) fill it.
#pragma once
#include <glm/glm.hpp>
#include <string>
#include <vector>

namespace gridrt {

// A glTF material mapped onto Whitted/Phong terms (README: "Material mapping").
struct Material {
  std::string name = "default";
  glm::vec3 base_color{0.8f};         // diffuse albedo (baseColorFactor.rgb)
  float metallic = 0.0f;              // 0 dielectric, 1 metal
  float roughness = 0.5f;             // 0 mirror-smooth .. 1 rough
  float transmission = 0.0f;          // KHR_materials_transmission: share refracted
  float ior = 1.5f;                   // KHR_materials_ior
  glm::vec3 attenuation_color{1.0f};  // KHR_materials_volume: colour after attenuation_distance
  float attenuation_distance = 0.0f;  // 0 = no absorption inside
  glm::vec3 emissive{0.0f};           // emissiveFactor * emissive_strength
  bool double_sided = true;
};

enum class LightType { Point, Spot, Directional };

// KHR_lights_punctual: point/spot intensity in candela, directional in lux.
struct Light {
  LightType type = LightType::Point;
  glm::vec3 color{1.0f};
  float intensity = 1.0f;
  glm::vec3 position{0.0f};
  glm::vec3 direction{0.0f, 0.0f, -1.0f};  // the way the light points (spot, directional)
  float inner_cone = 0.0f;                 // radians (spot)
  float outer_cone = 0.7853982f;           // radians (spot)
  float range = 0.0f;                      // 0 = infinite
};

struct Camera {
  std::string name;
  bool orthographic = false;
  float yfov = 0.6981317f;         // radians (perspective)
  float xmag = 1.0f, ymag = 1.0f;  // half extents (orthographic)
  float aspect = 0.0f;             // glTF aspectRatio, 0 if none: sizes an image given no size;
                                   // the rays always take the aspect of the image
  glm::mat4 world{1.0f};           // camera-to-world (looks down local -Z, +Y up)
};

struct Scene {
  // Triangle t has vertices positions[3t], [3t+1], [3t+2] (world space).
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;  // per triangle vertex, like positions; empty if none given
  std::vector<int> material_of;    // per triangle, index into materials
  std::vector<Material> materials;
  std::vector<Light> lights;
  Camera camera;
  bool has_camera = false;        // false: the renderer frames the bounding box
  bool has_lights = false;        // false: the renderer adds a default light
  size_t dropped_degenerate = 0;  // triangles skipped for NaN/Inf coordinates
  size_t dropped_zero_area = 0;   // triangles skipped for exactly zero area (repeated or
                                  // collinear vertices): never hit, and Moeller-Trumbore
                                  // would report garbage hits on repeated vertices
  size_t skipped_primitives = 0;  // non-triangle primitives skipped
  std::vector<std::string> warnings;

  size_t triangleCount() const { return positions.size() / 3; }
};

}  // namespace gridrt
