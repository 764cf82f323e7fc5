#include "gltf_writer.h"

#include <tiny_gltf.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <limits>
#include <sstream>

#include "errors.h"

#ifndef GRIDRT_VERSION
#define GRIDRT_VERSION "unknown"
#endif

namespace gridrt {
namespace {

// The glTF camera's clip planes mean nothing to a ray tracer but are required (perspective
// zfar is optional in glTF, yet tinygltf always writes it); generous values for viewers.
constexpr double kZNear = 0.01;
constexpr double kZFar = 1000.0;

// The shortest decimal that reads back as the same float, as a double: the JSON then says
// 0.63 rather than 0.6299999952316284, and (float) of what is read is still exact.
double tidy(float value) {
  if (!std::isfinite(value)) return value;
  char text[32];
  for (int digits = 6; digits < 9; ++digits) {
    std::snprintf(text, sizeof text, "%.*g", digits, static_cast<double>(value));
    if (std::strtof(text, nullptr) == value) return std::strtod(text, nullptr);
  }
  return value;
}

std::vector<double> tidy(glm::vec3 v) { return {tidy(v.x), tidy(v.y), tidy(v.z)}; }

tinygltf::Value number(float value) { return tinygltf::Value(tidy(value)); }

tinygltf::Value numbers(glm::vec3 v) {
  return tinygltf::Value(tinygltf::Value::Array{number(v.x), number(v.y), number(v.z)});
}

void useExtension(tinygltf::Model& model, const std::string& name) {
  auto& used = model.extensionsUsed;
  if (std::find(used.begin(), used.end(), name) == used.end()) used.push_back(name);
}

std::vector<double> columnMajor(const glm::mat4& m) {
  std::vector<double> out;
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) out.push_back(tidy(m[c][r]));
  return out;
}

// Throws unless the scene's arrays agree with each other.
void checkConsistent(const Scene& scene) {
  size_t n = scene.triangleCount();
  if (scene.positions.size() != 3 * n || scene.material_of.size() != n ||
      (!scene.normals.empty() && scene.normals.size() != scene.positions.size()))
    throw SceneError("cannot write glTF: scene arrays disagree (positions " +
                     std::to_string(scene.positions.size()) + ", normals " +
                     std::to_string(scene.normals.size()) + ", material_of " +
                     std::to_string(scene.material_of.size()) + ")");
  for (size_t t = 0; t < n; ++t) {
    int m = scene.material_of[t];
    if (m < 0 || static_cast<size_t>(m) >= scene.materials.size())
      throw SceneError("cannot write glTF: triangle " + std::to_string(t) + " has material " +
                       std::to_string(m) + " of " + std::to_string(scene.materials.size()));
  }
}

// Smallest extent of the bounding box of a material's triangles: the thicknessFactor of
// KHR_materials_volume (glTF viewers approximate refraction with it; 0 = thin-walled).
float thicknessOf(const Scene& scene, int material) {
  glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
  for (size_t t = 0; t < scene.triangleCount(); ++t) {
    if (scene.material_of[t] != material) continue;
    for (int k = 0; k < 3; ++k) {
      lo = glm::min(lo, scene.positions[3 * t + k]);
      hi = glm::max(hi, scene.positions[3 * t + k]);
    }
  }
  if (lo.x > hi.x) return 0.0f;
  glm::vec3 extent = hi - lo;
  return std::min({extent.x, extent.y, extent.z});
}

tinygltf::Material toGltf(const Scene& scene, int index, tinygltf::Model& model) {
  const Material& m = scene.materials[index];
  tinygltf::Material out;
  out.name = m.name;
  out.doubleSided = m.double_sided;
  auto& pbr = out.pbrMetallicRoughness;
  pbr.baseColorFactor = tidy(m.base_color);
  pbr.baseColorFactor.push_back(tidy(m.base_alpha));
  if (m.alpha_mode != AlphaMode::Opaque) {
    out.alphaMode = m.alpha_mode == AlphaMode::Mask ? "MASK" : "BLEND";
    out.alphaCutoff = tidy(m.alpha_cutoff);
  }
  pbr.metallicFactor = tidy(m.metallic);
  pbr.roughnessFactor = tidy(m.roughness);

  // emissiveFactor is limited to [0, 1]; any more goes into the strength.
  float peak = std::max({m.emissive.x, m.emissive.y, m.emissive.z});
  if (peak > 1.0f) {
    out.emissiveFactor = tidy(m.emissive / peak);
    out.extensions["KHR_materials_emissive_strength"] =
        tinygltf::Value(tinygltf::Value::Object{{"emissiveStrength", number(peak)}});
    useExtension(model, "KHR_materials_emissive_strength");
  } else {
    out.emissiveFactor = tidy(m.emissive);
  }
  if (m.transmission != 0.0f) {
    out.extensions["KHR_materials_transmission"] =
        tinygltf::Value(tinygltf::Value::Object{{"transmissionFactor", number(m.transmission)}});
    useExtension(model, "KHR_materials_transmission");
  }
  if (m.ior != 1.5f) {
    out.extensions["KHR_materials_ior"] =
        tinygltf::Value(tinygltf::Value::Object{{"ior", number(m.ior)}});
    useExtension(model, "KHR_materials_ior");
  }
  bool absorbs = m.attenuation_distance > 0.0f;
  if (m.transmission != 0.0f || absorbs) {
    tinygltf::Value::Object volume{{"thicknessFactor", number(thicknessOf(scene, index))}};
    if (absorbs) {
      volume["attenuationDistance"] = number(m.attenuation_distance);
      volume["attenuationColor"] = numbers(m.attenuation_color);
    }
    out.extensions["KHR_materials_volume"] = tinygltf::Value(std::move(volume));
    useExtension(model, "KHR_materials_volume");
  }
  return out;
}

// Appends bytes to the single buffer and returns a buffer view over them.
int addBufferView(tinygltf::Model& model, const void* data, size_t bytes, int target) {
  auto& buffer = model.buffers[0].data;
  tinygltf::BufferView view;
  view.buffer = 0;
  view.byteOffset = buffer.size();
  view.byteLength = bytes;
  view.target = target;
  const auto* first = static_cast<const unsigned char*>(data);
  buffer.insert(buffer.end(), first, first + bytes);
  model.bufferViews.push_back(view);
  return static_cast<int>(model.bufferViews.size()) - 1;
}

int addAccessor(tinygltf::Model& model, int view, int component_type, int type, size_t count) {
  tinygltf::Accessor accessor;
  accessor.bufferView = view;
  accessor.componentType = component_type;
  accessor.type = type;
  accessor.count = count;
  model.accessors.push_back(accessor);
  return static_cast<int>(model.accessors.size()) - 1;
}

// One node + mesh + primitive for triangles [first, end) of the scene, all of one material.
void addTriangleRun(const Scene& scene, size_t first, size_t end, tinygltf::Model& model) {
  size_t vertices = 3 * (end - first);
  const glm::vec3* positions = &scene.positions[3 * first];
  glm::vec3 lo = positions[0], hi = positions[0];
  for (size_t i = 0; i < vertices; ++i) {
    lo = glm::min(lo, positions[i]);
    hi = glm::max(hi, positions[i]);
  }
  static_assert(sizeof(glm::vec3) == 12, "vec3 must be three packed floats");

  tinygltf::Primitive primitive;
  primitive.mode = TINYGLTF_MODE_TRIANGLES;
  primitive.material = scene.material_of[first];
  int view =
      addBufferView(model, positions, vertices * sizeof(glm::vec3), TINYGLTF_TARGET_ARRAY_BUFFER);
  primitive.attributes["POSITION"] =
      addAccessor(model, view, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, vertices);
  model.accessors.back().minValues = {lo.x, lo.y, lo.z};  // required for POSITION
  model.accessors.back().maxValues = {hi.x, hi.y, hi.z};
  if (!scene.normals.empty()) {
    view = addBufferView(model, &scene.normals[3 * first], vertices * sizeof(glm::vec3),
                         TINYGLTF_TARGET_ARRAY_BUFFER);
    primitive.attributes["NORMAL"] =
        addAccessor(model, view, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, vertices);
  }
  std::vector<uint32_t> indices(vertices);
  for (size_t i = 0; i < vertices; ++i) indices[i] = static_cast<uint32_t>(i);
  view = addBufferView(model, indices.data(), indices.size() * sizeof(uint32_t),
                       TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
  primitive.indices = addAccessor(model, view, TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT,
                                  TINYGLTF_TYPE_SCALAR, vertices);

  tinygltf::Mesh mesh;
  mesh.name = scene.materials[primitive.material].name;
  mesh.primitives.push_back(primitive);
  model.meshes.push_back(mesh);
  tinygltf::Node node;
  node.name = mesh.name;
  node.mesh = static_cast<int>(model.meshes.size()) - 1;
  model.nodes.push_back(node);
}

void addCamera(const Camera& camera, tinygltf::Model& model) {
  tinygltf::Camera out;
  out.name = camera.name;
  if (camera.orthographic) {
    out.type = "orthographic";
    out.orthographic.xmag = tidy(camera.xmag);
    out.orthographic.ymag = tidy(camera.ymag);
    out.orthographic.znear = 0.0;
    out.orthographic.zfar = kZFar;
  } else {
    out.type = "perspective";
    out.perspective.yfov = tidy(camera.yfov);
    out.perspective.aspectRatio = tidy(camera.aspect);  // 0 is left out
    out.perspective.znear = kZNear;
    out.perspective.zfar = kZFar;
  }
  model.cameras.push_back(out);
  tinygltf::Node node;
  node.name = camera.name.empty() ? "camera" : camera.name;
  node.camera = static_cast<int>(model.cameras.size()) - 1;
  node.matrix = columnMajor(camera.world);
  model.nodes.push_back(node);
}

// glTF lights sit at their node's origin and shine down its local -Z.
glm::mat4 lightWorld(const Light& light) {
  auto unit = [](glm::vec3 v) { return v / glm::length(v); };  // exact on the axes
  glm::vec3 back = -unit(light.direction);
  glm::vec3 up = std::abs(back.y) < 0.9f ? glm::vec3(0, 1, 0) : glm::vec3(0, 0, 1);
  glm::vec3 right = unit(glm::cross(up, back));
  glm::mat4 world(1.0f);
  world[0] = glm::vec4(right, 0.0f);
  world[1] = glm::vec4(glm::cross(back, right), 0.0f);
  world[2] = glm::vec4(back, 0.0f);
  world[3] = glm::vec4(light.position, 1.0f);
  return world;
}

void addLight(const Light& light, tinygltf::Model& model) {
  tinygltf::Light out;
  out.color = tidy(light.color);
  out.intensity = tidy(light.intensity);
  out.range = tidy(light.range);
  switch (light.type) {
    case LightType::Point:
      out.type = "point";
      break;
    case LightType::Directional:
      out.type = "directional";
      break;
    case LightType::Spot:
      out.type = "spot";
      out.spot.innerConeAngle = tidy(light.inner_cone);
      out.spot.outerConeAngle = tidy(light.outer_cone);
      break;
  }
  model.lights.push_back(out);
  int index = static_cast<int>(model.lights.size()) - 1;

  tinygltf::Node node;
  node.name = "light " + std::to_string(index);
  if (light.type == LightType::Point)
    node.translation = tidy(light.position);
  else
    node.matrix = columnMajor(lightWorld(light));
  node.extensions["KHR_lights_punctual"] =
      tinygltf::Value(tinygltf::Value::Object{{"light", tinygltf::Value(index)}});
  model.nodes.push_back(node);
  useExtension(model, "KHR_lights_punctual");
}

tinygltf::Model toGltf(const Scene& scene) {
  tinygltf::Model model;
  model.asset.version = "2.0";
  model.asset.generator = "GridRT " GRIDRT_VERSION;
  model.buffers.resize(1);
  for (size_t m = 0; m < scene.materials.size(); ++m)
    model.materials.push_back(toGltf(scene, static_cast<int>(m), model));
  for (size_t first = 0, n = scene.triangleCount(); first < n;) {
    size_t end = first + 1;
    while (end < n && scene.material_of[end] == scene.material_of[first]) ++end;
    addTriangleRun(scene, first, end, model);
    first = end;
  }
  if (model.buffers[0].data.empty()) model.buffers.clear();
  if (scene.has_camera) addCamera(scene.camera, model);
  if (scene.has_lights)
    for (const Light& light : scene.lights) addLight(light, model);

  tinygltf::Scene root;
  for (size_t i = 0; i < model.nodes.size(); ++i) root.nodes.push_back(static_cast<int>(i));
  model.scenes.push_back(root);
  model.defaultScene = 0;
  return model;
}

bool endsWithGlb(const std::string& path) {
  if (path.size() < 4) return false;
  std::string ext = path.substr(path.size() - 4);
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return std::tolower(c); });
  return ext == ".glb";
}

}  // namespace

void writeGltf(const Scene& scene, const std::string& path) {
  checkConsistent(scene);
  tinygltf::Model model = toGltf(scene);
  bool binary = endsWithGlb(path);

  std::ostringstream encoded;
  tinygltf::TinyGLTF writer;
  if (!writer.WriteGltfSceneToStream(&model, encoded, /*prettyPrint=*/true, binary))
    throw RenderError("cannot encode glTF for '" + path + "'");
  const std::string bytes = encoded.str();

  const std::string temp = path + ".tmp" + std::to_string(::getpid());
  std::ofstream out(temp, std::ios::binary | std::ios::trunc);
  if (out) out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  if (out) out.close();
  if (!out) {
    std::string reason = std::strerror(errno);
    std::remove(temp.c_str());
    throw RenderError("cannot write glTF file '" + path + "': " + reason);
  }
  if (std::rename(temp.c_str(), path.c_str()) != 0) {
    std::string reason = std::strerror(errno);
    std::remove(temp.c_str());
    throw RenderError("cannot write glTF file '" + path + "': " + reason);
  }
}

}  // namespace gridrt
