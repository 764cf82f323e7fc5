// glTF 2.0 loader: tinygltf parses, this file validates every index and byte range it uses
// (tinygltf checks almost none) and flattens the node tree into world-space triangles.
// Behaviour and guarantees are listed in gltf_loader.h.
#include "gltf_loader.h"

#include <tiny_gltf.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <nlohmann/json.hpp>
#include <optional>
#include <string_view>
#include <system_error>

#include "errors.h"
#include "file_bytes.h"
#include "gltf_accessors.h"
#include "gltf_compressed_input.h"
#include "gltf_draco.h"
#include "gltf_meshopt.h"
#include "gltf_textures.h"
#include "gltf_vertex_attributes.h"
#include "mapped_file.h"
#include "parallel_loops.h"
#include "prefault.h"
#include "scene_triangles.h"
#include "uninitialized_vector.h"

namespace gridrt {
namespace {

namespace fs = std::filesystem;

// Decoded size above which a data URI is refused before tinygltf decodes it.
constexpr size_t kMaxDataUriBytes = size_t{256} << 20;
// JSON nesting deeper than this is refused: the JSON library frees (and tinygltf converts
// extras/extensions) recursively, so absurd nesting would overflow the stack.
constexpr int kMaxJsonDepth = 256;
// tinygltf takes lengths as unsigned int.
constexpr size_t kMaxInputBytes = std::numeric_limits<uint32_t>::max();
constexpr double kPi = 3.14159265358979323846;
// Triangles a core takes at a time when a primitive's triangles go to world space.
constexpr size_t kLoaderTriangleGrain = 4096;

// ---------------------------------------------------------------------------------------------
// Messages

using gltf::fail;
using gltf::named;
using gltf::oneLine;

// ---------------------------------------------------------------------------------------------
// Sandboxed file access for external URIs (buffers, images)
//
// tinygltf reads external files while it parses, so the check has to sit in its filesystem
// callbacks. It looks a URI up as JoinPath(base_dir, uri) and then as "./" + uri, and hands
// the callbacks only the joined path; the guard recovers the URI by stripping base_dir
// (always absolute here, so the "./" attempt never matches and is refused silently).

struct FileGuard {
  std::string base_dir;   // absolute, exactly as given to tinygltf; empty: no external files
  std::string rejection;  // the first refused URI and why, reported instead of tinygltf's error
};

bool hasParentComponent(const std::string& uri) {
  size_t start = 0;
  while (start <= uri.size()) {
    size_t end = uri.find_first_of("/\\", start);
    if (end == std::string::npos) end = uri.size();
    if (uri.compare(start, end - start, "..") == 0 && end - start == 2) return true;
    start = end + 1;
  }
  return false;
}

bool looksAbsolute(const std::string& uri) {
  if (uri.empty()) return false;
  if (uri[0] == '/' || uri[0] == '\\') return true;
  return uri.size() >= 2 && uri[1] == ':';  // a Windows drive letter
}

bool isInside(const fs::path& inner, const fs::path& outer) {
  return std::mismatch(outer.begin(), outer.end(), inner.begin(), inner.end()).first == outer.end();
}

// The URI part of a joined path, or nullopt if the path is not under base_dir.
std::optional<std::string> uriOf(const FileGuard& guard, const std::string& joined) {
  const std::string& base = guard.base_dir;
  if (base.empty()) return joined;
  if (joined.compare(0, base.size(), base) != 0) return std::nullopt;
  std::string uri = joined.substr(base.size());
  if (base.back() != '/' && !uri.empty() && uri[0] == '/') uri.erase(0, 1);
  return uri;
}

// Returns the file to read, or nullopt (recording why) if the path may not be read.
std::optional<fs::path> approvedPath(FileGuard& guard, const std::string& joined) {
  std::optional<std::string> uri = uriOf(guard, joined);
  if (!uri) return std::nullopt;
  auto refuse = [&](const std::string& why) -> std::optional<fs::path> {
    if (guard.rejection.empty()) guard.rejection = "external URI '" + *uri + "' " + why;
    return std::nullopt;
  };
  if (guard.base_dir.empty()) return refuse("cannot be read: no scene folder was given");
  if (uri->empty()) return refuse("is empty");
  if (looksAbsolute(*uri)) return refuse("is an absolute path (must be inside the scene folder)");
  if (hasParentComponent(*uri)) return refuse("contains '..' (must stay inside the scene folder)");
  std::error_code base_ec, target_ec;
  fs::path base = fs::weakly_canonical(guard.base_dir, base_ec);
  fs::path target = fs::weakly_canonical(fs::path(guard.base_dir) / *uri, target_ec);
  if (base_ec || target_ec)
    return refuse("cannot be resolved: " + (base_ec ? base_ec : target_ec).message());
  // Symbolic links may still lead out of the folder.
  if (!isInside(target, base)) return refuse("leads outside the scene folder");
  return target;
}

bool guardedFileExists(const std::string& path, void* user) {
  auto target = approvedPath(*static_cast<FileGuard*>(user), path);
  std::error_code ec;
  return target && fs::is_regular_file(*target, ec);
}

// The default expands "~" and environment variables (wordexp); URIs must not do that.
std::string identityPath(const std::string& path, void*) { return path; }

bool guardedReadFile(std::vector<unsigned char>* out, std::string* err, const std::string& path,
                     void* user) {
  auto target = approvedPath(*static_cast<FileGuard*>(user), path);
  if (!target) {
    if (err) *err += "refused to read " + path;
    return false;
  }
  std::ifstream in(*target, std::ios::binary);
  if (!in) {
    if (err) *err += std::string("cannot open ") + path + ": " + std::strerror(errno);
    return false;
  }
  if (!readStreamBytes(in, *out)) {
    if (err) *err += "read error in " + path;
    return false;
  }
  return true;
}

bool refuseWrite(std::string* err, const std::string&, const std::vector<unsigned char>&, void*) {
  if (err) *err += "the loader never writes files";
  return false;
}

// ---------------------------------------------------------------------------------------------
// Checks on the JSON text before tinygltf sees it

// The JSON text of a .glb (its first chunk), or the whole input for .gltf.
std::string_view jsonText(const unsigned char* data, size_t size, bool binary) {
  if (!binary) return {reinterpret_cast<const char*>(data), size};
  if (size < 20) return {};
  uint32_t chunk_length = 0;
  std::memcpy(&chunk_length, data + 12, 4);  // glTF is little-endian, like our hosts
  return {reinterpret_cast<const char*>(data) + 20, std::min<size_t>(chunk_length, size - 20)};
}

// Refuses data URIs whose decoded size would exceed kMaxDataUriBytes. A base64 string stops
// at its closing quote: tinygltf's decoder stops at the first non-base64 character anyway.
// A URI spelled with JSON escapes ("\u0064ata:") evades this scan, but then decodes to at
// most 3/4 of the input, which is already in memory.
void checkDataUris(std::string_view json, const std::string& label) {
  const std::string_view marker = "\"data:";
  for (size_t at = json.find(marker); at != std::string_view::npos;
       at = json.find(marker, at + 1)) {
    size_t end = json.find('"', at + 1);
    if (end == std::string_view::npos) end = json.size();
    size_t decoded = (end - at) / 4 * 3;
    if (decoded > kMaxDataUriBytes)
      fail(label, "data URI of about " + std::to_string(decoded >> 20) +
                      " MiB exceeds the limit of " + std::to_string(kMaxDataUriBytes >> 20) +
                      " MiB");
  }
}

void checkJsonDepth(std::string_view json, const std::string& label) {
  int depth = 0;
  bool in_string = false;
  for (size_t i = 0; i < json.size(); ++i) {
    char c = json[i];
    if (in_string) {
      if (c == '\\')
        ++i;
      else if (c == '"')
        in_string = false;
    } else if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      if (++depth > kMaxJsonDepth)
        fail(label, "JSON nested deeper than " + std::to_string(kMaxJsonDepth) + " levels");
    } else if (c == ']' || c == '}') {
      --depth;
    }
  }
}

void checkRequiredExtensions(const std::vector<std::string>& required, const std::string& label) {
  for (const std::string& ext : required) {
    bool supported = ext == "KHR_lights_punctual" || ext == "KHR_mesh_quantization" ||
                     ext == "KHR_draco_mesh_compression" || ext == "EXT_meshopt_compression" ||
                     ext.rfind("KHR_materials_", 0) == 0 || ext.rfind("KHR_texture_", 0) == 0 ||
                     ext.rfind("EXT_texture_", 0) == 0;
    if (!supported) fail(label, "requires extension " + ext + ", which is not supported");
  }
}

// The JSON's extensionsRequired, read before tinygltf parses the rest, so that an unknown
// extension is named instead of what tinygltf makes of the members it brings. Unreadable
// JSON is left to tinygltf's own message.
std::vector<std::string> requiredExtensions(const nlohmann::json& doc) {
  std::vector<std::string> out;
  if (!doc.is_object()) return out;
  auto it = doc.find("extensionsRequired");
  if (it == doc.end() || !it->is_array()) return out;
  for (const auto& ext : *it)
    if (ext.is_string()) out.push_back(ext.get<std::string>());
  return out;
}

// ---------------------------------------------------------------------------------------------
// Parsing

bool startsWithMagic(const unsigned char* data, size_t size) {
  return size >= 4 && std::memcmp(data, "glTF", 4) == 0;
}

tinygltf::Model parseModel(const unsigned char* data, size_t size, const std::string& base_dir,
                           const std::string& label, std::vector<std::string>& warnings) {
  if (size > kMaxInputBytes) fail(label, "larger than 4 GiB");
  const bool binary = startsWithMagic(data, size);
  if (binary && size >= 12) {
    uint32_t declared = 0;
    std::memcpy(&declared, data + 8, 4);
    if (declared > size)
      fail(label, "malformed glTF: truncated GLB (header declares " + std::to_string(declared) +
                      " bytes, got " + std::to_string(size) + ")");
  }
  std::string_view json = jsonText(data, size, binary);
  checkJsonDepth(json, label);
  checkDataUris(json, label);
  const nlohmann::json doc = nlohmann::json::parse(json.begin(), json.end(), nullptr, false);
  checkRequiredExtensions(requiredExtensions(doc), label);
  // What tinygltf cannot parse of compressed files, and a large .glb's binary chunk, set
  // aside until it has parsed the rest.
  const gltf::CompressedInput compressed = gltf::prepareCompressedInput(doc, data, size, binary);
  if (!compressed.bytes.empty()) {
    data = compressed.bytes.data();
    size = compressed.bytes.size();
    if (size > kMaxInputBytes) fail(label, "larger than 4 GiB");
  }

  FileGuard guard;
  if (!base_dir.empty()) {
    std::error_code ec;
    fs::path absolute = fs::absolute(base_dir, ec);
    if (ec) fail(label, "cannot resolve scene folder '" + base_dir + "': " + ec.message());
    guard.base_dir = absolute.lexically_normal().string();
  }

  tinygltf::TinyGLTF parser;
  parser.SetImageLoader(gltf::keepEncodedImage, nullptr);
  parser.SetFsCallbacks({guardedFileExists, identityPath, guardedReadFile, refuseWrite, &guard});

  tinygltf::Model model;
  std::string err, warn;
  bool ok = false;
  try {
    const auto length = static_cast<unsigned int>(size);
    ok = binary
             ? parser.LoadBinaryFromMemory(&model, &err, &warn, data, length, guard.base_dir)
             : parser.LoadASCIIFromString(&model, &err, &warn, reinterpret_cast<const char*>(data),
                                          length, guard.base_dir);
  } catch (const std::exception& e) {
    fail(label, std::string("malformed glTF: ") + e.what());
  }
  // A refused URI explains tinygltf's "File not found" better than tinygltf can.
  if (!guard.rejection.empty()) fail(label, guard.rejection);
  if (!ok) fail(label, "malformed glTF: " + (err.empty() ? "unknown error" : oneLine(err)));
  // tinygltf sometimes reports a problem and carries on (e.g. a misaligned GLB chunk).
  if (!err.empty()) warnings.push_back("glTF: " + oneLine(err));
  if (!warn.empty()) warnings.push_back("glTF: " + oneLine(warn));
  gltf::restoreCompressedInput(compressed, model);
  gltf::decodeMeshoptViews(model, label);  // first: a Draco buffer view may be one of them
  gltf::decodeDracoPrimitives(model, label);
  return model;
}

// ---------------------------------------------------------------------------------------------
// Accessors

// POSITION and NORMAL: FLOAT VEC3, or with KHR_mesh_quantization the integer types that
// extension allows (normalized or not for POSITION, normalized for NORMAL).
gltf::AccessorData readVec3(const tinygltf::Model& model, int index, const char* attribute,
                            bool quantized, const std::string& label) {
  gltf::AccessorData v = gltf::readAccessor(model, index, label);
  const bool is_normal = std::strcmp(attribute, "NORMAL") == 0;
  const bool integer_ok =
      quantized && (v.component_type == TINYGLTF_COMPONENT_TYPE_BYTE ||
                    v.component_type == TINYGLTF_COMPONENT_TYPE_SHORT ||
                    (!is_normal && (v.component_type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
                                    v.component_type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT)));
  const bool type_ok = v.component_type == TINYGLTF_COMPONENT_TYPE_FLOAT ||
                       (integer_ok && (v.normalized || !is_normal));
  if (!type_ok || v.type != TINYGLTF_TYPE_VEC3)
    fail(label, "accessor " + std::to_string(index) + ": " + attribute +
                    " must be FLOAT VEC3, not " + gltf::componentName(v.component_type) + " " +
                    gltf::typeName(v.type) + (v.normalized ? " normalized" : "") +
                    (quantized ? "" : " (integer attributes need KHR_mesh_quantization)"));
  return v;
}

gltf::AccessorData readIndices(const tinygltf::Model& model, int index, const std::string& label) {
  gltf::AccessorData v = gltf::readAccessor(model, index, label);
  bool unsigned_int = v.component_type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
                      v.component_type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT ||
                      v.component_type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
  if (!unsigned_int || v.type != TINYGLTF_TYPE_SCALAR)
    fail(label, "accessor " + std::to_string(index) +
                    ": indices must be UNSIGNED_BYTE/SHORT/INT SCALAR, not " +
                    gltf::componentName(v.component_type) + " " + gltf::typeName(v.type));
  return v;
}

// ---------------------------------------------------------------------------------------------
// Transforms (double precision, cast to float per vertex)

// Rotation matrix of the quaternion (x, y, z, w), normalised first.
glm::dmat3 rotationMatrix(double x, double y, double z, double w) {
  const double n = std::sqrt(x * x + y * y + z * z + w * w);
  x /= n, y /= n, z /= n, w /= n;
  glm::dmat3 r;  // r[column][row]
  r[0] = {1 - 2 * (y * y + z * z), 2 * (x * y + z * w), 2 * (x * z - y * w)};
  r[1] = {2 * (x * y - z * w), 1 - 2 * (x * x + z * z), 2 * (y * z + x * w)};
  r[2] = {2 * (x * z + y * w), 2 * (y * z - x * w), 1 - 2 * (x * x + y * y)};
  return r;
}

void requireLength(const std::vector<double>& v, size_t n, const char* property,
                   const std::string& node, const std::string& label) {
  if (!v.empty() && v.size() != n)
    fail(label, node + ": " + property + " must have " + std::to_string(n) + " numbers, not " +
                    std::to_string(v.size()));
}

glm::dmat4 localTransform(const tinygltf::Node& node, const std::string& where,
                          const std::string& label) {
  requireLength(node.matrix, 16, "matrix", where, label);
  requireLength(node.translation, 3, "translation", where, label);
  requireLength(node.rotation, 4, "rotation", where, label);
  requireLength(node.scale, 3, "scale", where, label);
  glm::dmat4 m(1.0);
  if (node.matrix.size() == 16) {
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 4; ++r) m[c][r] = node.matrix[size_t(c * 4 + r)];  // column-major
    return m;
  }
  if (node.rotation.size() == 4) {
    const auto& q = node.rotation;
    if (q[0] == 0 && q[1] == 0 && q[2] == 0 && q[3] == 0)
      fail(label, where + ": rotation quaternion is zero");
    m = glm::dmat4(rotationMatrix(q[0], q[1], q[2], q[3]));
  }
  if (node.scale.size() == 3)
    for (int c = 0; c < 3; ++c) m[c] *= node.scale[size_t(c)];
  if (node.translation.size() == 3)
    m[3] = glm::dvec4(node.translation[0], node.translation[1], node.translation[2], 1.0);
  return m;
}

glm::dvec3 transformPoint(const glm::dmat4& m, const glm::dvec3& p) {
  return glm::dvec3(m * glm::dvec4(p, 1.0));
}

// Camera-to-world without scale or shear: keeps the viewing direction (-Z) and the up
// vector's plane, as renderers expect a rigid camera frame.
std::optional<glm::mat4> rigidFrame(const glm::dmat4& world) {
  glm::dvec3 z(world[2]), y(world[1]);
  glm::dvec3 x = glm::cross(y, z);
  if (!(glm::length(z) > 0.0) || !(glm::length(x) > 0.0)) return std::nullopt;
  z = glm::normalize(z);
  x = glm::normalize(x);
  y = glm::cross(z, x);
  glm::dmat4 out(1.0);
  out[0] = glm::dvec4(x, 0.0);
  out[1] = glm::dvec4(y, 0.0);
  out[2] = glm::dvec4(z, 0.0);
  out[3] = world[3];
  glm::mat4 f(out);
  for (int c = 0; c < 4; ++c)
    if (!isFinite(glm::vec3(f[c]))) return std::nullopt;
  return f;
}

// ---------------------------------------------------------------------------------------------
// Materials

double numberOr(const tinygltf::Value& object, const char* key, double fallback) {
  if (!object.Has(key)) return fallback;
  const tinygltf::Value& v = object.Get(key);
  return v.IsNumber() ? v.GetNumberAsDouble() : fallback;
}

glm::vec3 colorOr(const tinygltf::Value& object, const char* key, glm::vec3 fallback) {
  if (!object.Has(key)) return fallback;
  const tinygltf::Value& v = object.Get(key);
  if (!v.IsArray() || v.ArrayLen() != 3) return fallback;
  glm::vec3 c;
  for (int i = 0; i < 3; ++i) {
    if (!v.Get(i).IsNumber()) return fallback;
    c[i] = float(v.Get(i).GetNumberAsDouble());
  }
  return c;
}

const tinygltf::Value& extension(const tinygltf::ExtensionMap& map, const char* name) {
  static const tinygltf::Value kNone;
  auto it = map.find(name);
  return it == map.end() ? kNone : it->second;
}

Material convertMaterial(const tinygltf::Material& m, size_t index) {
  Material out;
  out.name = m.name.empty() ? "material " + std::to_string(index) : m.name;
  const auto& pbr = m.pbrMetallicRoughness;
  if (pbr.baseColorFactor.size() >= 3)
    out.base_color = {pbr.baseColorFactor[0], pbr.baseColorFactor[1], pbr.baseColorFactor[2]};
  if (pbr.baseColorFactor.size() >= 4) out.base_alpha = float(pbr.baseColorFactor[3]);
  out.alpha_mode = m.alphaMode == "MASK"    ? AlphaMode::Mask
                   : m.alphaMode == "BLEND" ? AlphaMode::Blend
                                            : AlphaMode::Opaque;
  out.alpha_cutoff = float(m.alphaCutoff);
  out.metallic = float(pbr.metallicFactor);
  out.roughness = float(pbr.roughnessFactor);
  out.double_sided = m.doubleSided;

  out.transmission = float(
      numberOr(extension(m.extensions, "KHR_materials_transmission"), "transmissionFactor", 0.0));
  out.ior = float(numberOr(extension(m.extensions, "KHR_materials_ior"), "ior", 1.5));

  const tinygltf::Value& volume = extension(m.extensions, "KHR_materials_volume");
  out.attenuation_color = colorOr(volume, "attenuationColor", glm::vec3(1.0f));
  // glTF's default distance is +infinity, i.e. no absorption, which Material stores as 0.
  const double distance = numberOr(volume, "attenuationDistance", 0.0);
  out.attenuation_distance = std::isfinite(distance) && distance > 0.0 ? float(distance) : 0.0f;

  const double strength =
      numberOr(extension(m.extensions, "KHR_materials_emissive_strength"), "emissiveStrength", 1.0);
  if (m.emissiveFactor.size() == 3)
    out.emissive = glm::vec3(
        glm::dvec3(m.emissiveFactor[0], m.emissiveFactor[1], m.emissiveFactor[2]) * strength);
  return out;
}

// ---------------------------------------------------------------------------------------------
// Lights and cameras

std::optional<Light> convertLight(const tinygltf::Light& l, const glm::dmat4& world,
                                  const std::string& where, const std::string& label,
                                  std::vector<std::string>& warnings) {
  Light out;
  if (l.type == "point")
    out.type = LightType::Point;
  else if (l.type == "spot")
    out.type = LightType::Spot;
  else if (l.type == "directional")
    out.type = LightType::Directional;
  else {
    warnings.push_back(where + ": light type '" + l.type + "' is not supported; ignored");
    return std::nullopt;
  }
  // tinygltf leaves `color` empty when absent; the spec default is white.
  if (l.color.size() == 3)
    out.color = {l.color[0], l.color[1], l.color[2]};
  else if (!l.color.empty())
    fail(label, where + ": light color must have 3 numbers");
  out.intensity = float(l.intensity);
  out.range = float(l.range);
  out.inner_cone = float(l.spot.innerConeAngle);
  out.outer_cone = float(l.spot.outerConeAngle);
  out.position = glm::vec3(transformPoint(world, glm::dvec3(0.0)));
  glm::dvec3 dir = glm::dmat3(world) * glm::dvec3(0.0, 0.0, -1.0);
  if (!(glm::length(dir) > 0.0) || !std::isfinite(glm::length(dir)))
    fail(label, where + ": light transform is degenerate");
  out.direction = glm::vec3(glm::normalize(dir));
  if (!isFinite(out.position) || !isFinite(out.direction))
    fail(label, where + ": light transform is not finite");
  return out;
}

Camera convertCamera(const tinygltf::Camera& c, const glm::dmat4& world, const std::string& where,
                     const std::string& label) {
  Camera out;
  out.name = c.name;
  if (c.type == "perspective") {
    const double yfov = c.perspective.yfov;
    if (!(yfov > 0.0 && yfov < kPi)) fail(label, where + ": perspective yfov must be in (0, pi)");
    out.yfov = float(yfov);
    out.aspect = std::isfinite(c.perspective.aspectRatio) && c.perspective.aspectRatio > 0
                     ? float(c.perspective.aspectRatio)
                     : 0.0f;
  } else if (c.type == "orthographic") {
    const double xmag = std::abs(c.orthographic.xmag), ymag = std::abs(c.orthographic.ymag);
    if (!(xmag > 0.0 && std::isfinite(xmag) && ymag > 0.0 && std::isfinite(ymag)))
      fail(label, where + ": orthographic xmag and ymag must be non-zero and finite");
    out.orthographic = true;
    out.xmag = float(xmag);
    out.ymag = float(ymag);
  } else {
    fail(label, where + ": camera type '" + c.type + "' is neither perspective nor orthographic");
  }
  std::optional<glm::mat4> frame = rigidFrame(world);
  if (!frame) fail(label, where + ": camera transform is degenerate");
  out.world = *frame;
  return out;
}

// ---------------------------------------------------------------------------------------------
// Scene building

class SceneBuilder {
 public:
  SceneBuilder(const tinygltf::Model& model, const std::string& label,
               const GltfLoadOptions& options, const ScenePose* pose = nullptr)
      : model_(model), label_(label), options_(options), pose_(pose) {}

  Scene build(std::vector<std::string> parse_warnings) {
    scene_.warnings = std::move(parse_warnings);
    checkRequiredExtensions(model_.extensionsRequired, label_);
    convertMaterials();
    traverse(rootNodes());
    if (scene_.positions.empty()) fail(label_, "the scene has no triangles");
    // Triangles from primitives without NORMAL keep the face normal addTriangle gave them.
    finishNormals(any_normals_, scene_);
    gltf::finishVertexAttributes(scene_);
    chooseCamera();
    scene_.has_lights = !scene_.lights.empty();
    addDropWarnings(scene_);
    for (std::string& w : scene_.warnings) w = oneLine(w);  // names may hold newlines
    return std::move(scene_);
  }

 private:
  struct CameraNode {
    int node;
    glm::dmat4 world;
  };

  std::string nodeName(int index) const {
    return named("node", size_t(index), model_.nodes[size_t(index)].name);
  }

  void convertMaterials() {
    gltf::convertTextures(model_, label_, scene_);
    for (size_t i = 0; i < model_.materials.size(); ++i) {
      scene_.materials.push_back(convertMaterial(model_.materials[i], i));
      gltf::convertMaterialTextures(model_, model_.materials[i], i, label_, scene_.materials.back(),
                                    scene_.warnings);
    }
  }

  std::vector<int> rootNodes() const {
    if (model_.scenes.empty()) {
      // No scene: every node that is nobody's child, in index order.
      std::vector<bool> is_child(model_.nodes.size(), false);
      for (const auto& node : model_.nodes)
        for (int child : node.children)
          if (child >= 0 && size_t(child) < is_child.size()) is_child[size_t(child)] = true;
      std::vector<int> roots;
      for (size_t i = 0; i < model_.nodes.size(); ++i)
        if (!is_child[i]) roots.push_back(int(i));
      return roots;
    }
    int index = model_.defaultScene >= 0 ? model_.defaultScene : 0;
    if (size_t(index) >= model_.scenes.size())
      fail(label_, "default scene " + std::to_string(index) + " does not exist (" +
                       std::to_string(model_.scenes.size()) + " scenes)");
    return model_.scenes[size_t(index)].nodes;
  }

  // Depth-first, children in file order, a node before its children. An explicit stack
  // keeps hostile, deep hierarchies off the call stack.
  void traverse(const std::vector<int>& roots) {
    struct Entry {
      int node;
      glm::dmat4 parent_world;
      bool leaving;  // marks the end of the node's subtree
    };
    enum : char { kUnseen, kOnPath, kDone };
    std::vector<char> state(model_.nodes.size(), kUnseen);
    std::vector<Entry> stack;
    // World matrices first, so that a skin can find its joints wherever they are.
    std::vector<std::pair<int, glm::dmat4>> visits;
    world_of_node_.assign(model_.nodes.size(), std::nullopt);
    for (auto it = roots.rbegin(); it != roots.rend(); ++it)
      stack.push_back({*it, glm::dmat4(1.0), false});
    while (!stack.empty()) {
      Entry e = stack.back();
      stack.pop_back();
      if (e.leaving) {
        state[size_t(e.node)] = kDone;
        continue;
      }
      if (e.node < 0 || size_t(e.node) >= model_.nodes.size())
        fail(label_, "node " + std::to_string(e.node) + " does not exist (" +
                         std::to_string(model_.nodes.size()) + " nodes)");
      char& s = state[size_t(e.node)];
      if (s == kOnPath) fail(label_, nodeName(e.node) + ": the node hierarchy has a cycle");
      if (s == kDone)
        fail(label_, nodeName(e.node) + ": reached twice (a node may have only one parent)");
      s = kOnPath;
      const tinygltf::Node& node = model_.nodes[size_t(e.node)];
      const glm::dmat4 world = e.parent_world * posedLocalTransform(e.node, node);
      visits.push_back({e.node, world});
      world_of_node_[size_t(e.node)] = world;
      stack.push_back({e.node, glm::dmat4(1.0), true});
      for (auto it = node.children.rbegin(); it != node.children.rend(); ++it)
        stack.push_back({*it, world, false});
    }
    for (const auto& [index, world] : visits) visit(index, world);
  }

  void visit(int index, const glm::dmat4& world) {
    const tinygltf::Node& node = model_.nodes[size_t(index)];
    if (node.mesh >= 0)
      addMesh(node.mesh, world, index);
    else if (node.skin >= 0)
      scene_.warnings.push_back(nodeName(index) + ": skin without a mesh; ignored");
    if (node.camera >= 0) {
      if (size_t(node.camera) >= model_.cameras.size())
        fail(label_,
             nodeName(index) + ": camera " + std::to_string(node.camera) + " does not exist");
      camera_nodes_.push_back({index, world});
    }
    addLight(node, index, world);
  }

  void addLight(const tinygltf::Node& node, int index, const glm::dmat4& world) {
    const tinygltf::Value& ext = extension(node.extensions, "KHR_lights_punctual");
    if (!ext.Has("light")) return;
    const tinygltf::Value& v = ext.Get("light");
    const double light = v.IsNumber() ? v.GetNumberAsDouble() : -1.0;
    if (!(light >= 0.0 && light < double(model_.lights.size()) && light == std::floor(light)))
      fail(label_, nodeName(index) + ": KHR_lights_punctual light index does not exist (" +
                       std::to_string(model_.lights.size()) + " lights)");
    const tinygltf::Light& l = model_.lights[size_t(light)];
    std::string where = nodeName(index) + " " + named("light", size_t(light), l.name);
    if (auto converted = convertLight(l, world, where, label_, scene_.warnings))
      scene_.lights.push_back(*converted);
  }

  void addMesh(int mesh_index, const glm::dmat4& world, int node_index) {
    if (size_t(mesh_index) >= model_.meshes.size())
      fail(label_,
           nodeName(node_index) + ": mesh " + std::to_string(mesh_index) + " does not exist");
    const tinygltf::Mesh& mesh = model_.meshes[size_t(mesh_index)];
    const tinygltf::Node& node = model_.nodes[size_t(node_index)];
    // The morph weights: the pose's, else the node's, else the mesh's, else zero.
    const std::vector<double>& weights = posedMorphWeights(node_index, node, mesh);
    std::optional<std::vector<glm::dmat4>> joints;
    if (node.skin >= 0) joints = jointMatrices(node.skin, node_index);
    for (size_t p = 0; p < mesh.primitives.size(); ++p)
      addPrimitive(mesh.primitives[p],
                   named("mesh", size_t(mesh_index), mesh.name) + " primitive " + std::to_string(p),
                   world, weights, joints ? &*joints : nullptr);
  }

  // The pose's entry for node `index`, or null (the still pose).
  const NodePose* poseOf(int index) const {
    return pose_ && size_t(index) < pose_->size() ? &(*pose_)[size_t(index)] : nullptr;
  }

  // The node's local matrix with the pose's translation, rotation and scale in place of
  // the file's where it sets them (through localTransform, as a file holding them would).
  glm::dmat4 posedLocalTransform(int index, const tinygltf::Node& node) const {
    const NodePose* pose = poseOf(index);
    if (!pose || !pose->movesTransform()) return localTransform(node, nodeName(index), label_);
    tinygltf::Node trs;
    trs.translation =
        pose->translation
            ? std::vector<double>{pose->translation->x, pose->translation->y, pose->translation->z}
            : node.translation;
    trs.rotation = pose->rotation ? std::vector<double>{pose->rotation->x, pose->rotation->y,
                                                        pose->rotation->z, pose->rotation->w}
                                  : node.rotation;
    trs.scale = pose->scale ? std::vector<double>{pose->scale->x, pose->scale->y, pose->scale->z}
                            : node.scale;
    return localTransform(trs, nodeName(index), label_);
  }

  // The morph weights of a node's mesh: the pose's, else the node's, else the mesh's.
  const std::vector<double>& posedMorphWeights(int index, const tinygltf::Node& node,
                                               const tinygltf::Mesh& mesh) const {
    const NodePose* pose = poseOf(index);
    if (pose && pose->weights) return *pose->weights;
    return node.weights.empty() ? mesh.weights : node.weights;
  }

  // Per joint of skin `skin_index`: the joint node's world matrix times its inverse bind
  // matrix (identity where the skin has none), the matrix a vertex bound to it moves by.
  std::vector<glm::dmat4> jointMatrices(int skin_index, int node_index) const {
    if (size_t(skin_index) >= model_.skins.size())
      fail(label_,
           nodeName(node_index) + ": skin " + std::to_string(skin_index) + " does not exist");
    const tinygltf::Skin& skin = model_.skins[size_t(skin_index)];
    const std::string where = named("skin", size_t(skin_index), skin.name);
    std::optional<gltf::AccessorData> inverse_bind;
    if (skin.inverseBindMatrices >= 0) {
      inverse_bind = gltf::readAccessor(model_, skin.inverseBindMatrices, label_);
      if (inverse_bind->type != TINYGLTF_TYPE_MAT4 ||
          inverse_bind->component_type != TINYGLTF_COMPONENT_TYPE_FLOAT ||
          inverse_bind->count != skin.joints.size())
        fail(label_, where + ": inverseBindMatrices must be " + std::to_string(skin.joints.size()) +
                         " FLOAT MAT4");
    }
    std::vector<glm::dmat4> out;
    for (size_t j = 0; j < skin.joints.size(); ++j) {
      const int joint = skin.joints[j];
      if (joint < 0 || size_t(joint) >= model_.nodes.size() || !world_of_node_[size_t(joint)])
        fail(label_, where + ": joint " + std::to_string(joint) +
                         " is not a node of the scene being loaded");
      out.push_back(*world_of_node_[size_t(joint)] *
                    (inverse_bind ? inverse_bind->mat4(j) : glm::dmat4(1.0)));
    }
    return out;
  }

  int materialIndex(int material, const std::string& where) {
    if (material >= 0) {
      if (size_t(material) >= model_.materials.size())
        fail(label_, where + ": material " + std::to_string(material) + " does not exist");
      return material;
    }
    if (default_material_ < 0) {
      default_material_ = int(scene_.materials.size());
      scene_.materials.push_back(Material{});
    }
    return default_material_;
  }

  static int attribute(const tinygltf::Primitive& prim, const char* name) {
    auto it = prim.attributes.find(name);
    return it == prim.attributes.end() ? -1 : it->second;
  }

  // A morph target's or skin attribute's accessor, which must have one element per vertex.
  gltf::AccessorData perVertex(int accessor, const std::string& what, size_t vertex_count,
                               const std::string& where) const {
    gltf::AccessorData data = gltf::readAccessor(model_, accessor, label_);
    if (data.count != vertex_count)
      fail(label_, where + ": " + what + " has " + std::to_string(data.count) + " elements for " +
                       std::to_string(vertex_count) + " vertices");
    return data;
  }

  // Adds the weighted morph-target displacements of `attribute` to `data` (VEC3).
  void applyMorphTargets(const tinygltf::Primitive& prim, const std::vector<double>& weights,
                         const char* attribute, gltf::AccessorData& data,
                         const std::string& where) const {
    for (size_t t = 0; t < prim.targets.size() && t < weights.size(); ++t) {
      auto it = prim.targets[t].find(attribute);
      if (it == prim.targets[t].end() || weights[t] == 0.0) continue;
      const std::string what = "morph target " + std::to_string(t) + " " + attribute;
      const gltf::AccessorData delta = perVertex(it->second, what, data.count, where);
      if (delta.type != TINYGLTF_TYPE_VEC3) fail(label_, where + ": " + what + " must be VEC3");
      for (size_t i = 0; i < 3 * data.count; ++i) data.values[i] += weights[t] * delta.values[i];
    }
  }

  // Per vertex, the skin matrix: the joint matrices weighted by JOINTS_n / WEIGHTS_n, the
  // weights normalised to sum 1 (some files' do not). Vertices whose weights are all zero
  // keep the node's own transform (`world`).
  std::vector<glm::dmat4> skinMatrices(const tinygltf::Primitive& prim,
                                       const std::vector<glm::dmat4>& joints,
                                       const glm::dmat4& world, size_t vertex_count,
                                       const std::string& where) {
    std::vector<glm::dmat4> sum(vertex_count, glm::dmat4(0.0));
    std::vector<double> total(vertex_count, 0.0);
    for (int set = 0;; ++set) {
      const std::string j_name = "JOINTS_" + std::to_string(set);
      const std::string w_name = "WEIGHTS_" + std::to_string(set);
      const int j_index = attribute(prim, j_name.c_str()),
                w_index = attribute(prim, w_name.c_str());
      if (j_index < 0 && w_index < 0) break;
      if (j_index < 0 || w_index < 0)
        fail(label_,
             where + ": " +
                 (j_index < 0 ? w_name + " without " + j_name : j_name + " without " + w_name));
      const gltf::AccessorData j = perVertex(j_index, j_name, vertex_count, where);
      const gltf::AccessorData w = perVertex(w_index, w_name, vertex_count, where);
      if (j.type != TINYGLTF_TYPE_VEC4 || w.type != TINYGLTF_TYPE_VEC4)
        fail(label_, where + ": " + j_name + " and " + w_name + " must be VEC4");
      for (size_t v = 0; v < vertex_count; ++v)
        for (int k = 0; k < 4; ++k) {
          const double weight = w.at(v, k);
          if (weight == 0.0) continue;
          const double joint = j.at(v, k);
          if (!(weight > 0.0) || !(joint < double(joints.size())))
            fail(label_,
                 where + ": vertex " + std::to_string(v) + ": " +
                     (weight > 0.0 ? j_name + " names joint " + std::to_string(uint64_t(joint)) +
                                         " of " + std::to_string(joints.size())
                                   : w_name + " is negative or NaN"));
          sum[v] += weight * joints[size_t(joint)];
          total[v] += weight;
        }
    }
    size_t unweighted = 0;
    for (size_t v = 0; v < vertex_count; ++v) {
      if (total[v] > 0.0) {
        sum[v] /= total[v];
      } else {
        sum[v] = world;
        ++unweighted;
      }
    }
    if (unweighted > 0)
      scene_.warnings.push_back(where + ": " + std::to_string(unweighted) +
                                " skinned vertices without joint weights keep the node's "
                                "transform");
    return sum;
  }

  void addPrimitive(const tinygltf::Primitive& prim, const std::string& where,
                    const glm::dmat4& world, const std::vector<double>& morph_weights,
                    const std::vector<glm::dmat4>* joints) {
    if (prim.mode < -1 || prim.mode > TINYGLTF_MODE_TRIANGLE_FAN)
      fail(label_, where + ": mode " + std::to_string(prim.mode) + " is not a glTF mode");
    if (prim.mode != TINYGLTF_MODE_TRIANGLES && prim.mode != -1) {
      ++scene_.skipped_primitives;
      return;
    }
    const int position_index = attribute(prim, "POSITION");
    if (position_index < 0) {
      // The spec asks to skip primitives without positions.
      scene_.warnings.push_back(where + ": no POSITION attribute; skipped");
      ++scene_.skipped_primitives;
      return;
    }
    // Used where they were read (no copy: a mesh of millions of vertices had spent a sixth
    // of its load copying them).
    gltf::AccessorData positions = readVec3(model_, position_index, "POSITION", quantized_, label_);
    const size_t vertex_count = positions.count;
    std::optional<gltf::AccessorData> normals;
    if (int n = attribute(prim, "NORMAL"); n >= 0) {
      normals = readVec3(model_, n, "NORMAL", quantized_, label_);
      if (normals->count != vertex_count)
        fail(label_, "accessor " + std::to_string(n) + ": NORMAL count " +
                         std::to_string(normals->count) + " differs from POSITION count " +
                         std::to_string(vertex_count));
    }
    const gltf::VertexAttributes extras =
        gltf::readVertexAttributes(model_, prim, vertex_count, quantized_, where, label_);
    applyMorphTargets(prim, morph_weights, "POSITION", positions, where);
    if (normals) applyMorphTargets(prim, morph_weights, "NORMAL", *normals, where);
    const UninitializedVector<uint32_t> indices = triangleIndices(prim, vertex_count, where);
    const int material = materialIndex(prim.material, where);
    // A skinned mesh moves with its joints; the node's own transform does not apply (glTF).
    const bool skinned = joints && attribute(prim, "JOINTS_0") >= 0;
    const std::vector<glm::dmat4> skin =
        skinned ? skinMatrices(prim, *joints, world, vertex_count, where)
                : std::vector<glm::dmat4>();
    const glm::dmat3 normal_matrix = glm::transpose(glm::inverse(glm::dmat3(world)));
    const bool node_mirrored = glm::determinant(glm::dmat3(world)) < 0.0;
    // The scene's arrays grown once for the whole primitive (pushing into them had regrown
    // and faulted in tens of MB piece by piece on one core).
    const size_t count = indices.size() / 3, first = scene_.material_of.size();
    reserveMoreFaultedIn(scene_.positions, 3 * count);
    reserveMoreFaultedIn(scene_.normals, 3 * count);
    reserveMoreFaultedIn(scene_.material_of, count);
    scene_.positions.resize(3 * (first + count));
    scene_.normals.resize(3 * (first + count));
    scene_.material_of.resize(first + count, material);

    // A skinned triangle mirrors where its first vertex's skin matrix does.
    auto mirrors = [&](size_t t) {
      return skinned ? glm::determinant(glm::dmat3(skin[indices[3 * t]])) < 0.0 : node_mirrored;
    };
    // First every triangle in world space, on all cores, into its place as if all were kept
    // (a mesh of a million triangles had spent a fifth of its load here on one core); each
    // triangle's arithmetic is what it was one at a time, so the scene does not depend on
    // the number of cores.
    std::vector<TriangleVerdict> verdicts(count);
    parallelForDynamic(size_t(0), count, kLoaderTriangleGrain, [&](size_t t) {
      glm::vec3 p[3], n[3];
      for (int k = 0; k < 3; ++k) {
        const size_t vertex = indices[3 * t + size_t(k)];
        const glm::dmat4& m = skinned ? skin[vertex] : world;
        p[k] = glm::vec3(transformPoint(m, positions.vec3(vertex)));
        const glm::dmat3 to_world =
            skinned ? glm::transpose(glm::inverse(glm::dmat3(m))) : normal_matrix;
        // Zero marks "no usable normal" (absent, zero or NaN in the file).
        n[k] =
            normals ? unitOr(to_world * normals->vec3(vertex), glm::vec3(0.0f)) : glm::vec3(0.0f);
      }
      verdicts[t] = triangleVerdict(p);
      if (verdicts[t] != TriangleVerdict::Kept) return;
      // The glTF spec: a mirroring transform turns the winding clockwise; swap it back.
      if (mirrors(t)) std::swap(p[1], p[2]), std::swap(n[1], n[2]);
      const size_t at = 3 * (first + t);
      triangleCorners(p, n, &scene_.positions[at], &scene_.normals[at]);
    });
    // Then, in order, the dropped triangles counted and squeezed out, and the kept ones'
    // vertex attributes appended.
    const bool attributes = gltf::appendsTriangleAttributes(extras, scene_);
    size_t kept = 0;
    for (size_t t = 0; t < count; ++t) {
      if (!countVerdict(verdicts[t], scene_)) continue;
      if (kept != t) {
        std::copy_n(&scene_.positions[3 * (first + t)], 3, &scene_.positions[3 * (first + kept)]);
        std::copy_n(&scene_.normals[3 * (first + t)], 3, &scene_.normals[3 * (first + kept)]);
      }
      if (attributes) {
        uint32_t stored[3] = {indices[3 * t], indices[3 * t + 1], indices[3 * t + 2]};
        if (mirrors(t)) std::swap(stored[1], stored[2]);
        glm::vec4 tangents[3];
        for (int k = 0; k < 3; ++k)
          tangents[k] = gltf::worldTangent(extras, stored[k], skinned ? skin[stored[k]] : world);
        gltf::appendTriangleAttributes(extras, stored, tangents, first + kept, scene_);
      }
      ++kept;
    }
    scene_.positions.resize(3 * (first + kept));
    scene_.normals.resize(3 * (first + kept));
    scene_.material_of.resize(first + kept);
    any_normals_ = any_normals_ || (normals.has_value() && kept > 0);
  }

  // The primitive's vertex indices, three per triangle, all checked against vertex_count
  // (on all cores: a mesh of millions of vertices; the first index out of range is the one
  // reported).
  UninitializedVector<uint32_t> triangleIndices(const tinygltf::Primitive& prim,
                                                size_t vertex_count,
                                                const std::string& where) const {
    UninitializedVector<uint32_t> out;
    if (prim.indices < 0) {
      if (vertex_count % 3 != 0)
        fail(label_, where + ": " + std::to_string(vertex_count) +
                         " vertices is not a multiple of 3 for triangles");
      if (vertex_count > std::numeric_limits<uint32_t>::max())
        fail(label_, where + ": too many vertices");
      reserveFaultedIn(out, vertex_count);
      out.resize(vertex_count);
      parallelFor(size_t(0), vertex_count, [&](size_t i) { out[i] = uint32_t(i); });
      return out;
    }
    const gltf::AccessorData indices = readIndices(model_, prim.indices, label_);
    if (indices.count % 3 != 0)
      fail(label_, "accessor " + std::to_string(prim.indices) + ": " +
                       std::to_string(indices.count) +
                       " indices is not a multiple of 3 for triangles");
    reserveFaultedIn(out, indices.count);
    out.resize(indices.count);
    std::vector<size_t> first_bad(size_t(parallelSliceCount()), indices.count);
    parallelSlices(int(first_bad.size()), [&](int me, int slices) {
      const auto [begin, end] = sliceRange(indices.count, me, slices);
      for (size_t i = begin; i < end; ++i) {
        out[i] = uint32_t(indices.at(i, 0));
        if (out[i] >= vertex_count && first_bad[size_t(me)] == indices.count)
          first_bad[size_t(me)] = i;
      }
    });
    const size_t bad = *std::min_element(first_bad.begin(), first_bad.end());
    if (bad < indices.count)
      fail(label_, "accessor " + std::to_string(prim.indices) + ": index " +
                       std::to_string(out[bad]) + " out of range for " +
                       std::to_string(vertex_count) + " vertices");
    return out;
  }

  void chooseCamera() {
    if (camera_nodes_.empty()) {
      if (!options_.camera_name.empty())
        throw UsageError(oneLine(label_ + ": --camera '" + options_.camera_name +
                                 "' not found: the scene has no camera"));
      return;
    }
    const CameraNode* chosen = &camera_nodes_.front();
    if (!options_.camera_name.empty()) {
      chosen = nullptr;
      // A number picks the camera at that position in traversal order (as listed below).
      const std::string& wanted = options_.camera_name;
      const bool numeric =
          std::all_of(wanted.begin(), wanted.end(), ::isdigit) && wanted.size() < 9;
      std::string available;
      for (size_t i = 0; i < camera_nodes_.size(); ++i) {
        const CameraNode& c = camera_nodes_[i];
        const tinygltf::Node& node = model_.nodes[size_t(c.node)];
        const std::string& camera_name = model_.cameras[size_t(node.camera)].name;
        const bool match =
            numeric ? std::stoul(wanted) == i : camera_name == wanted || node.name == wanted;
        if (!chosen && match) chosen = &c;
        available += (available.empty() ? "" : ", ") + std::to_string(i) + " = " +
                     named("camera", size_t(node.camera), camera_name) + " on " + nodeName(c.node);
      }
      // The name came from the command line: a usage error, not a broken file.
      if (!chosen)
        throw UsageError(
            oneLine(label_ + ": camera '" + wanted + "' not found; available: " + available));
    }
    const tinygltf::Node& node = model_.nodes[size_t(chosen->node)];
    scene_.camera =
        convertCamera(model_.cameras[size_t(node.camera)], chosen->world,
                      nodeName(chosen->node) + " camera " + std::to_string(node.camera), label_);
    scene_.has_camera = true;
  }

  const tinygltf::Model& model_;
  const std::string& label_;
  const GltfLoadOptions& options_;
  const ScenePose* pose_;  // null: the still pose
  Scene scene_;
  bool any_normals_ = false;  // some triangle came from a primitive with NORMAL
  std::vector<CameraNode> camera_nodes_;
  int default_material_ = -1;
  // Per node: its world matrix, once the traversal has reached it.
  std::vector<std::optional<glm::dmat4>> world_of_node_;
  // The file declares KHR_mesh_quantization: integer POSITION and NORMAL are allowed.
  bool quantized_ = std::find(model_.extensionsUsed.begin(), model_.extensionsUsed.end(),
                              "KHR_mesh_quantization") != model_.extensionsUsed.end();
};

[[noreturn]] void cannotOpen(const std::string& path, const std::string& reason) {
  throw SceneError(oneLine("cannot open scene '" + path + "': " + reason));
}

void openSceneFile(const std::string& path, MappedFile& file) {
  std::error_code ec;
  if (fs::is_directory(path, ec)) cannotOpen(path, "is a directory");
  std::string error;
  if (!file.open(path, error)) cannotOpen(path, error);
}

}  // namespace

Scene loadGltfFromMemory(const unsigned char* data, size_t size, const std::string& base_dir,
                         const std::string& label, const GltfLoadOptions& options) {
  return GltfDocument::fromMemory(data, size, base_dir, label).flatten(options);
}

Scene loadGltfFile(const std::string& path, const GltfLoadOptions& options) {
  return GltfDocument::fromFile(path).flatten(options);
}

GltfDocument::GltfDocument(std::shared_ptr<const tinygltf::Model> model, std::string label,
                           std::vector<std::string> warnings)
    : model_(std::move(model)), label_(std::move(label)), parse_warnings_(std::move(warnings)) {}

GltfDocument GltfDocument::fromMemory(const unsigned char* data, size_t size,
                                      const std::string& base_dir, const std::string& label) {
  std::vector<std::string> warnings;
  auto model =
      std::make_shared<const tinygltf::Model>(parseModel(data, size, base_dir, label, warnings));
  return GltfDocument(std::move(model), label, std::move(warnings));
}

Scene GltfDocument::flatten(const GltfLoadOptions& options, const ScenePose* pose) const {
  return SceneBuilder(*model_, label_, options, pose).build(parse_warnings_);
}

GltfDocument GltfDocument::fromFile(const std::string& path) {
  MappedFile bytes;
  openSceneFile(path, bytes);

  // A .glb must carry the magic; anything else is sniffed by loadGltfFromMemory.
  std::string ext = fs::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return char(std::tolower(c)); });
  if (ext == ".glb" && !startsWithMagic(bytes.data(), bytes.size()))
    fail(path, "not a binary glTF (missing 'glTF' magic)");

  // External files live next to the scene ("." for a bare file name: empty would forbid them).
  fs::path base_dir = fs::path(path).parent_path();
  if (base_dir.empty()) base_dir = ".";
  return fromMemory(bytes.data(), bytes.size(), base_dir.string(), path);
}

}  // namespace gridrt
