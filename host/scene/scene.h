// The scene as the renderer sees it: world-space triangles in global load order, their
// materials, the lights and the camera. Loaders (glTF, the built-in default scene) fill it.
#pragma once
#include <glm/glm.hpp>
#include <string>
#include <vector>

namespace gridrt {

// How a texture is sampled (a glTF sampler): wrap modes per axis, and the filters.
enum class TextureWrap { Repeat, ClampToEdge, MirroredRepeat };
enum class TextureFilter { Linear, Nearest };

// A glTF texture: an image of Scene::images and how it is sampled.
struct Texture {
  int image = -1;  // into Scene::images
  TextureWrap wrap_s = TextureWrap::Repeat, wrap_t = TextureWrap::Repeat;
  TextureFilter mag_filter = TextureFilter::Linear;
  TextureFilter min_filter = TextureFilter::Linear;
  bool mipmaps = true;  // minification reads the mip levels (glTF's default, *_MIPMAP_*)
};

// A material's use of a texture (a glTF textureInfo): the texture, the TEXCOORD set and
// KHR_texture_transform as an affine map of (u, v, 1): u' = dot(map_u, (u, v, 1)), v' =
// dot(map_v, (u, v, 1)).
struct TextureSlot {
  int texture = -1;  // into Scene::textures; -1: the material has none here
  int texcoord = 0;  // TEXCOORD_0 or TEXCOORD_1
  glm::vec3 map_u{1.0f, 0.0f, 0.0f}, map_v{0.0f, 1.0f, 0.0f};
  bool used() const { return texture >= 0; }
};

// One level of a decoded image: RGBA texels, row 0 at the top (glTF's v = 0), linear.
struct TexelLevel {
  int width = 0, height = 0;
  std::vector<glm::vec4> texels;  // width * height, row-major
};

// A decoded image as lookups read it: level 0 the image, each next level half the size
// (rounded down, at least 1) down to 1x1; empty until decoded.
struct TexelImage {
  std::vector<TexelLevel> levels;
  bool empty() const { return levels.empty(); }
};

// An image of the file. The loader keeps its encoded bytes (PNG, JPEG, ...) and never
// decodes them: the scene library links no image decoder. decodeTextures (host/texture)
// fills the texels each use needs.
struct SceneImage {
  std::string name;       // for messages, e.g. "image 2 'wood'"
  std::string mime_type;  // as the file says, may be empty
  std::string uri;        // an external file's name, else empty
  std::vector<unsigned char> encoded;
  TexelImage colour;  // base colour and emissive lookups: the sRGB transfer undone
  TexelImage data;    // metallic-roughness and occlusion lookups: the values as stored
};

// How a material's alpha (base colour alpha x texture alpha x COLOR_0 alpha) is used
// (glTF alphaMode; docs/gltf.md, "Alpha"): ignored; a cut-out (below the cutoff the
// surface is a hole every ray passes); a partial transmission (alpha of the light stays).
enum class AlphaMode { Opaque, Mask, Blend };

// A glTF material mapped onto Whitted/Phong terms (docs/gltf.md, "Material mapping").
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
  float base_alpha = 1.0f;  // baseColorFactor's alpha
  AlphaMode alpha_mode = AlphaMode::Opaque;
  float alpha_cutoff = 0.5f;  // Mask: alpha below it is a hole
  // Whether rays may pass this material's surfaces (Mask holes, Blend's partial alpha).
  bool seeThrough() const { return alpha_mode != AlphaMode::Opaque; }
  // Textures: base colour (times base_color, sRGB), metallic (B) and roughness (G) times
  // their factors, emissive (times emissive, sRGB), occlusion (R, scales the ambient term).
  // Normal map: tangent-space normals (RGB as stored) scaled in x and y by normal_scale.
  TextureSlot base_color_texture, metallic_roughness_texture, emissive_texture, occlusion_texture,
      normal_texture;
  float occlusion_strength = 1.0f;
  float normal_scale = 1.0f;
  bool textured() const {
    return base_color_texture.used() || metallic_roughness_texture.used() ||
           emissive_texture.used() || occlusion_texture.used() || normal_texture.used();
  }
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
  // TEXCOORD_0 and TEXCOORD_1 per triangle vertex, like positions; each empty when no
  // primitive has it ((0, 0) for the vertices of those without).
  std::vector<glm::vec2> texcoords[2];
  // COLOR_0 per triangle vertex (RGBA, linear); empty when no primitive has it (white for
  // the vertices of those without).
  std::vector<glm::vec4> colors;
  // TANGENT per triangle vertex: a world-space unit tangent and in w the bitangent's sign
  // (+1 or -1, mirroring transforms included); empty when no primitive has it, zero for the
  // vertices of those without (their normal maps then take tangents from the UVs).
  std::vector<glm::vec4> tangents;
  std::vector<int> material_of;  // per triangle, index into materials
  std::vector<Material> materials;
  std::vector<Texture> textures;
  std::vector<SceneImage> images;
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
