// glTF images, samplers and textures, kept encoded for host/texture to decode
// (gltf_textures.h).
#include "gltf_textures.h"

#include <algorithm>
#include <cmath>

#include "gltf_accessors.h"

namespace gridrt::gltf {
namespace {

// glTF sampler constants (the specification's WebGL enums).
constexpr int kNearest = 9728, kLinear = 9729;
constexpr int kNearestMipmapNearest = 9984, kLinearMipmapNearest = 9985;
constexpr int kNearestMipmapLinear = 9986, kLinearMipmapLinear = 9987;
constexpr int kClampToEdge = 33071, kMirroredRepeat = 33648, kRepeat = 10497;

void warnOnce(std::vector<std::string>& warnings, const std::string& warning) {
  if (std::find(warnings.begin(), warnings.end(), warning) == warnings.end())
    warnings.push_back(warning);
}

TextureWrap wrapMode(int wrap, const std::string& where, const std::string& label) {
  switch (wrap) {
    case kRepeat:
      return TextureWrap::Repeat;
    case kClampToEdge:
      return TextureWrap::ClampToEdge;
    case kMirroredRepeat:
      return TextureWrap::MirroredRepeat;
    default:
      fail(label, where + ": wrap mode " + std::to_string(wrap) + " is not a glTF wrap mode");
  }
}

Texture convertTexture(const tinygltf::Model& model, const tinygltf::Texture& t, size_t index,
                       const std::string& label) {
  const std::string where = named("texture", index, t.name);
  Texture out;
  if (t.source >= 0 && size_t(t.source) >= model.images.size())
    fail(label, where + ": image " + std::to_string(t.source) + " does not exist");
  out.image = t.source;
  if (t.sampler < 0) return out;
  if (size_t(t.sampler) >= model.samplers.size())
    fail(label, where + ": sampler " + std::to_string(t.sampler) + " does not exist");
  const tinygltf::Sampler& s = model.samplers[size_t(t.sampler)];
  const std::string sampler = named("sampler", size_t(t.sampler), s.name);
  out.wrap_s = wrapMode(s.wrapS, sampler, label);
  out.wrap_t = wrapMode(s.wrapT, sampler, label);
  if (s.magFilter == kNearest) out.mag_filter = TextureFilter::Nearest;
  switch (s.minFilter) {
    case kNearest:
      out.min_filter = TextureFilter::Nearest;
      out.mipmaps = false;
      break;
    case kLinear:
      out.mipmaps = false;
      break;
    case kNearestMipmapNearest:
    case kNearestMipmapLinear:
      out.min_filter = TextureFilter::Nearest;
      break;
    case kLinearMipmapNearest:
    case kLinearMipmapLinear:
    default:  // undefined: the viewer's choice, mip-mapped and linear
      break;
  }
  return out;
}

double numberOr(const tinygltf::Value& object, const char* key, double fallback) {
  if (!object.Has(key)) return fallback;
  const tinygltf::Value& v = object.Get(key);
  return v.IsNumber() ? v.GetNumberAsDouble() : fallback;
}

// A pair of numbers (offset, scale) of KHR_texture_transform, or `fallback`.
glm::dvec2 pairOr(const tinygltf::Value& object, const char* key, glm::dvec2 fallback) {
  if (!object.Has(key)) return fallback;
  const tinygltf::Value& v = object.Get(key);
  if (!v.IsArray() || v.ArrayLen() != 2 || !v.Get(0).IsNumber() || !v.Get(1).IsNumber())
    return fallback;
  return {v.Get(0).GetNumberAsDouble(), v.Get(1).GetNumberAsDouble()};
}

// A textureInfo (index, texCoord, extensions) as a slot; an unusable one is returned
// unused, with a warning.
TextureSlot textureSlot(const tinygltf::Model& model, int index, int texcoord,
                        const tinygltf::ExtensionMap& extensions, const std::string& where,
                        const std::string& label, std::vector<std::string>& warnings) {
  TextureSlot slot;
  if (index < 0) return slot;
  if (size_t(index) >= model.textures.size())
    fail(label, where + ": texture " + std::to_string(index) + " does not exist");
  if (model.textures[size_t(index)].source < 0) {
    warnOnce(warnings, named("texture", size_t(index), model.textures[size_t(index)].name) +
                           " has no image a glTF 2.0 reader can decode (an extension's "
                           "source?); ignored");
    return slot;
  }
  // KHR_texture_transform: uv' = T * R * S * (u, v, 1), R turning the UVs counter-clockwise
  // in glTF's UV space, whose v axis points down: u' = cos u + sin v, v' = -sin u + cos v.
  // That is what the Khronos sample TextureTransformTest (its arrow on the green marker),
  // Babylon.js, three.js and Blender's importer do; the GLSL listing in the extension's text
  // has the opposite sign (its matrix is counter-clockwise with v up), a known erratum.
  auto it = extensions.find("KHR_texture_transform");
  glm::dvec2 offset(0.0), scale(1.0);
  double rotation = 0.0;
  if (it != extensions.end()) {
    const tinygltf::Value& t = it->second;
    offset = pairOr(t, "offset", offset);
    scale = pairOr(t, "scale", scale);
    rotation = numberOr(t, "rotation", 0.0);
    const double coord = numberOr(t, "texCoord", double(texcoord));
    texcoord = coord >= 0.0 && coord <= 2.0 ? int(coord) : -1;
  }
  if (texcoord != 0 && texcoord != 1) {
    warnOnce(warnings, where + ": TEXCOORD_" + std::to_string(texcoord) +
                           " is not supported (only TEXCOORD_0 and _1); texture ignored");
    return slot;
  }
  const double c = std::cos(rotation), s = std::sin(rotation);
  slot.texture = index;
  slot.texcoord = texcoord;
  slot.map_u = glm::vec3(glm::dvec3(c * scale.x, s * scale.y, offset.x));
  slot.map_v = glm::vec3(glm::dvec3(-s * scale.x, c * scale.y, offset.y));
  if (!std::isfinite(slot.map_u.x + slot.map_u.y + slot.map_u.z + slot.map_v.x + slot.map_v.y +
                     slot.map_v.z))
    fail(label, where + ": KHR_texture_transform is not finite");
  return slot;
}

}  // namespace

bool keepEncodedImage(tinygltf::Image* image, int, std::string*, std::string*, int, int,
                      const unsigned char* bytes, int size, void*) {
  if (image->bufferView >= 0) return true;  // convertImages reads it, range checked
  image->image.assign(bytes, bytes + std::max(size, 0));
  image->as_is = true;
  return true;
}

void convertTextures(const tinygltf::Model& model, const std::string& label, Scene& scene) {
  for (size_t i = 0; i < model.images.size(); ++i) {
    const tinygltf::Image& image = model.images[i];
    SceneImage out;
    out.name = named("image", i, image.name);
    out.mime_type = image.mimeType;
    out.uri = image.uri;
    if (image.bufferView >= 0) {
      const ViewBytes bytes = bufferViewBytes(model, image.bufferView, out.name, label);
      out.encoded.assign(bytes.data, bytes.data + bytes.size);
    } else {
      out.encoded = image.image;
    }
    scene.images.push_back(std::move(out));
  }
  for (size_t i = 0; i < model.textures.size(); ++i)
    scene.textures.push_back(convertTexture(model, model.textures[i], i, label));
}

void convertMaterialTextures(const tinygltf::Model& model, const tinygltf::Material& m,
                             size_t index, const std::string& label, Material& out,
                             std::vector<std::string>& warnings) {
  const std::string where = named("material", index, m.name);
  const auto& pbr = m.pbrMetallicRoughness;
  auto slot = [&](const auto& info, const char* name) {
    return textureSlot(model, info.index, info.texCoord, info.extensions, where + " " + name, label,
                       warnings);
  };
  out.base_color_texture = slot(pbr.baseColorTexture, "baseColorTexture");
  out.metallic_roughness_texture = slot(pbr.metallicRoughnessTexture, "metallicRoughnessTexture");
  out.emissive_texture = slot(m.emissiveTexture, "emissiveTexture");
  out.occlusion_texture = slot(m.occlusionTexture, "occlusionTexture");
  out.occlusion_strength = float(std::clamp(m.occlusionTexture.strength, 0.0, 1.0));
  out.normal_texture = slot(m.normalTexture, "normalTexture");
  out.normal_scale = float(m.normalTexture.scale);
  // Material extensions name their textures "...Texture" (transmissionTexture, ...).
  for (const auto& [name, value] : m.extensions)
    for (const std::string& key : value.Keys())
      if (key.size() >= 7 && key.compare(key.size() - 7, 7, "Texture") == 0)
        warnOnce(warnings, name + " " + key + " is ignored");
}

}  // namespace gridrt::gltf
