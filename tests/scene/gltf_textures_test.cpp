// The loader's side of textures and vertex colours (gltf_textures.h,
// gltf_vertex_attributes.h): images kept encoded from buffer views, data URIs and files
// beside the scene; samplers, texture slots and KHR_texture_transform; TEXCOORD_0/1 and
// COLOR_0 per triangle vertex; the errors and warnings. Documents are built here.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <string>
#include <vector>

#include "errors.h"
#include "gltf_loader.h"
#include "test_support.h"

namespace gridrt {
namespace {

using test::bytesOf;

// Products of a float cosine or sine of a quarter turn with small factors: a few ulps.
constexpr float kTransformTolerance = 1e-6f;

// One buffer (a data URI) of 4-byte aligned views, an accessor per view.
class Document {
 public:
  // A view over `bytes`; returns its index.
  int view(const std::string& bytes) {
    views_.push_back("{\"buffer\":0,\"byteOffset\":" + std::to_string(bin_.size()) +
                     ",\"byteLength\":" + std::to_string(bytes.size()) + "}");
    bin_ += bytes;
    bin_.resize((bin_.size() + 3) / 4 * 4, '\0');
    return int(views_.size() - 1);
  }
  // A view given as JSON; returns its index.
  int rawView(const std::string& json) {
    views_.push_back(json);
    return int(views_.size() - 1);
  }
  // An accessor over a new view of `bytes`; `extra`: further members.
  int accessor(const std::string& bytes, int component_type, size_t count, const std::string& type,
               const std::string& extra = "") {
    accessors_.push_back("{\"bufferView\":" + std::to_string(view(bytes)) + ",\"componentType\":" +
                         std::to_string(component_type) + ",\"count\":" + std::to_string(count) +
                         ",\"type\":\"" + type + "\"" + extra + "}");
    return int(accessors_.size() - 1);
  }
  // `rest`: the other top-level members, without braces.
  std::string json(const std::string& rest) const {
    return "{\"asset\":{\"version\":\"2.0\"},\"buffers\":[{\"byteLength\":" +
           std::to_string(bin_.size()) + ",\"uri\":\"data:application/octet-stream;base64," +
           test::base64(bin_) + "\"}],\"bufferViews\":[" + join(views_) + "],\"accessors\":[" +
           join(accessors_) + "]," + rest + "}";
  }

 private:
  static std::string join(const std::vector<std::string>& items) {
    std::string out;
    for (const auto& s : items) out += (out.empty() ? "" : ",") + s;
    return out;
  }
  std::string bin_;
  std::vector<std::string> views_, accessors_;
};

constexpr int kUByte = 5121, kByte = 5120, kUShort = 5123, kFloat = 5126;

const std::vector<float> kTriangle = {0, 0, 0, 1, 0, 0, 0, 1, 0};

// One node with one mesh of `primitives`, and the `extra` members.
std::string meshScene(const std::string& primitives, const std::string& extra = "") {
  return "\"scene\":0,\"scenes\":[{\"nodes\":[0]}],\"nodes\":[{\"mesh\":0}],"
         "\"meshes\":[{\"primitives\":[" +
         primitives + "]}]" + (extra.empty() ? "" : "," + extra);
}

Scene load(const std::string& json, const std::string& dir = "") {
  return loadGltfFromMemory(reinterpret_cast<const unsigned char*>(json.data()), json.size(), dir,
                            "test.gltf");
}

std::string errorOf(const std::string& json) {
  return test::errorOf<SceneError>([&] { load(json); });
}

bool hasWarning(const Scene& s, const std::string& text) {
  return std::any_of(s.warnings.begin(), s.warnings.end(),
                     [&](const std::string& w) { return w.find(text) != std::string::npos; });
}

TEST(GltfTextures, ImagesKeepTheirEncodedBytesFromViewsDataUrisAndFiles) {
  Document d;
  const int pos = d.accessor(bytesOf(kTriangle), kFloat, 3, "VEC3");
  const int png_view = d.view("first image bytes");
  const std::string dir = test::freshDir("images");
  std::ofstream(dir + "/beside.png", std::ios::binary) << "third image bytes";
  const std::string json = d.json(meshScene(
      "{\"attributes\":{\"POSITION\":" + std::to_string(pos) + "}}",
      "\"images\":[{\"bufferView\":" + std::to_string(png_view) +
          ",\"mimeType\":\"image/png\"},"
          "{\"uri\":\"data:image/png;base64," +
          test::base64("second image bytes") + "\"},{\"uri\":\"beside.png\",\"name\":\"third\"}]"));
  const Scene s = load(json, dir);
  ASSERT_EQ(s.images.size(), 3u);
  auto text = [](const SceneImage& i) { return std::string(i.encoded.begin(), i.encoded.end()); };
  EXPECT_EQ(text(s.images[0]), "first image bytes");
  EXPECT_EQ(s.images[0].mime_type, "image/png");
  EXPECT_EQ(text(s.images[1]), "second image bytes");
  EXPECT_EQ(text(s.images[2]), "third image bytes");
  EXPECT_EQ(s.images[2].uri, "beside.png");
  EXPECT_EQ(s.images[2].name, "image 2 'third'");
  EXPECT_TRUE(s.images[0].colour.empty());  // never decoded by the loader
}

TEST(GltfTextures, AnImageViewOutsideItsBufferIsAnError) {
  Document d;
  const int pos = d.accessor(bytesOf(kTriangle), kFloat, 3, "VEC3");
  const int view = d.rawView("{\"buffer\":0,\"byteOffset\":8,\"byteLength\":1000}");
  const std::string message = errorOf(d.json(meshScene(
      "{\"attributes\":{\"POSITION\":" + std::to_string(pos) + "}}",
      "\"images\":[{\"bufferView\":" + std::to_string(view) + ",\"mimeType\":\"image/png\"}]")));
  EXPECT_NE(message.find("image 0: bufferView 1"), std::string::npos) << message;
}

// A material whose slots name texture 0 (sampler 0) with the given textureInfo members.
std::string texturedMaterial(const std::string& base_info, const std::string& emissive_info,
                             const std::string& sampler) {
  return "\"images\":[{\"uri\":\"data:image/png;base64,AAAA\"}],"
         "\"samplers\":[" +
         sampler +
         "],\"textures\":[{\"source\":0,\"sampler\":0}],"
         "\"materials\":[{\"pbrMetallicRoughness\":{\"baseColorTexture\":" +
         base_info +
         ",\"metallicRoughnessTexture\":{\"index\":0}},\"emissiveTexture\":" + emissive_info +
         ",\"occlusionTexture\":{\"index\":0,\"strength\":0.25}}]";
}

std::string triangleWithMaterial(Document& d) {
  const int pos = d.accessor(bytesOf(kTriangle), kFloat, 3, "VEC3");
  return "{\"attributes\":{\"POSITION\":" + std::to_string(pos) + "},\"material\":0}";
}

TEST(GltfTextures, SamplersSlotsAndTextureTransforms) {
  Document d;
  const std::string prim = triangleWithMaterial(d);
  const Scene s = load(d.json(
      meshScene(prim, texturedMaterial("{\"index\":0,\"texCoord\":1}",
                                       "{\"index\":0,\"extensions\":{\"KHR_texture_transform\":{"
                                       "\"offset\":[0.5,0.25],\"rotation\":1.5707963267948966,"
                                       "\"scale\":[2,3],\"texCoord\":1}}}",
                                       "{\"magFilter\":9728,\"minFilter\":9729,\"wrapS\":33071,"
                                       "\"wrapT\":33648}"))));
  ASSERT_EQ(s.textures.size(), 1u);
  const Texture& t = s.textures[0];
  EXPECT_EQ(t.image, 0);
  EXPECT_EQ(t.wrap_s, TextureWrap::ClampToEdge);
  EXPECT_EQ(t.wrap_t, TextureWrap::MirroredRepeat);
  EXPECT_EQ(t.mag_filter, TextureFilter::Nearest);
  EXPECT_EQ(t.min_filter, TextureFilter::Linear);
  EXPECT_FALSE(t.mipmaps);  // LINEAR without MIPMAP
  const Material& m = s.materials[0];
  EXPECT_EQ(m.base_color_texture.texture, 0);
  EXPECT_EQ(m.base_color_texture.texcoord, 1);
  EXPECT_EQ(m.base_color_texture.map_u, glm::vec3(1, 0, 0));
  EXPECT_EQ(m.base_color_texture.map_v, glm::vec3(0, 1, 0));
  EXPECT_EQ(m.metallic_roughness_texture.texture, 0);
  EXPECT_EQ(m.occlusion_texture.texture, 0);
  EXPECT_FLOAT_EQ(m.occlusion_strength, 0.25f);
  // uv' = T R S uv with R counter-clockwise in UV space (v down), as the Khronos sample
  // TextureTransformTest and the viewers draw it: a quarter turn gives u' = 0.5 + 3 v and
  // v' = 0.25 - 2 u (the extension's GLSL listing, with the opposite sign, gave 0.5 - 3 v).
  const TextureSlot& e = m.emissive_texture;
  EXPECT_EQ(e.texcoord, 1);
  const glm::vec3 want_u(0.0f, 3.0f, 0.5f), want_v(-2.0f, 0.0f, 0.25f);
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(e.map_u[c], want_u[c], kTransformTolerance);
    EXPECT_NEAR(e.map_v[c], want_v[c], kTransformTolerance);
  }
}

TEST(GltfTextures, NoSamplerMeansRepeatLinearMipmapped) {
  Document d;
  const std::string prim = triangleWithMaterial(d);
  std::string extra = texturedMaterial("{\"index\":0}", "{\"index\":0}", "{}");
  extra.replace(extra.find(",\"sampler\":0"), std::string(",\"sampler\":0").size(), "");
  const Scene s = load(d.json(meshScene(prim, extra)));
  const Texture& t = s.textures[0];
  EXPECT_EQ(t.wrap_s, TextureWrap::Repeat);
  EXPECT_EQ(t.wrap_t, TextureWrap::Repeat);
  EXPECT_EQ(t.mag_filter, TextureFilter::Linear);
  EXPECT_TRUE(t.mipmaps);
}

TEST(GltfTextures, BadTextureReferencesAreErrorsNamingThem) {
  Document d;
  const std::string prim = triangleWithMaterial(d);
  const std::string good = texturedMaterial("{\"index\":0}", "{\"index\":0}", "{}");
  auto with = [&](const std::string& from, const std::string& to) {
    std::string extra = good;
    extra.replace(extra.find(from), from.size(), to);
    return errorOf(d.json(meshScene(prim, extra)));
  };
  EXPECT_NE(with("\"baseColorTexture\":{\"index\":0}", "\"baseColorTexture\":{\"index\":3}")
                .find("baseColorTexture: texture 3 does not exist"),
            std::string::npos);
  EXPECT_NE(with("\"source\":0", "\"source\":2").find("texture 0: image 2 does not exist"),
            std::string::npos);
  EXPECT_NE(with("\"sampler\":0}", "\"sampler\":4}").find("texture 0: sampler 4 does not exist"),
            std::string::npos);
  EXPECT_NE(with("\"samplers\":[{}]", "\"samplers\":[{\"wrapS\":7}]")
                .find("sampler 0: wrap mode 7 is not a glTF wrap mode"),
            std::string::npos);
}

TEST(GltfTextures, IgnoredTexturesAreWarnings) {
  Document d;
  const std::string prim = triangleWithMaterial(d);
  std::string extra = texturedMaterial("{\"index\":0,\"texCoord\":2}", "{\"index\":0}", "{}");
  extra.replace(extra.find("\"emissiveTexture\""), 0,
                "\"alphaMode\":\"BLEND\",\"extensions\":{\"KHR_materials_transmission\":{"
                "\"transmissionTexture\":{\"index\":0}}},");
  const Scene s = load(d.json(meshScene(prim, extra)));
  EXPECT_FALSE(s.materials[0].base_color_texture.used());
  EXPECT_TRUE(hasWarning(s, "baseColorTexture: TEXCOORD_2 is not supported"));
  EXPECT_TRUE(hasWarning(s, "KHR_materials_transmission transmissionTexture is ignored"));
  EXPECT_EQ(s.materials[0].alpha_mode, AlphaMode::Blend);  // supported: no warning
  for (const std::string& w : s.warnings) EXPECT_EQ(w.find("alphaMode"), std::string::npos) << w;
}

TEST(GltfTextures, NormalMapsAndWorldTangents) {
  Document d;
  const int pos = d.accessor(bytesOf(kTriangle), kFloat, 3, "VEC3");
  const int tangent = d.accessor(bytesOf(std::vector<float>{2, 0, 0, 1, 0, 3, 0, -1, 0, 0, 0, 1}),
                                 kFloat, 3, "VEC4");
  std::string extra = texturedMaterial("{\"index\":0}", "{\"index\":0}", "{}");
  extra.replace(extra.find("\"emissiveTexture\""), 0,
                "\"normalTexture\":{\"index\":0,\"scale\":0.5},");
  std::string json =
      d.json(meshScene("{\"attributes\":{\"POSITION\":" + std::to_string(pos) +
                           ",\"TANGENT\":" + std::to_string(tangent) + "},\"material\":0}",
                       extra));
  // Mirrored in x: tangents mirror, their bitangent sign flips, vertices 1 and 2 swap.
  json.replace(json.find("{\"mesh\":0}"), 10, "{\"mesh\":0,\"scale\":[-1,1,1]}");
  const Scene s = load(json);
  EXPECT_EQ(s.materials[0].normal_texture.texture, 0);
  EXPECT_FLOAT_EQ(s.materials[0].normal_scale, 0.5f);
  ASSERT_EQ(s.tangents.size(), 3u);
  EXPECT_EQ(s.tangents[0], glm::vec4(-1, 0, 0, -1));  // unit, w flipped
  EXPECT_EQ(s.tangents[1], glm::vec4(0, 0, 0, 0));    // the zero tangent: none
  EXPECT_EQ(s.tangents[2], glm::vec4(0, 1, 0, 1));    // w -1, flipped to +1
  EXPECT_FALSE(hasWarning(s, "normal"));
}

TEST(GltfTextures, TexcoordsAndColoursPerTriangleVertex) {
  Document d;
  const int pos = d.accessor(bytesOf(kTriangle), kFloat, 3, "VEC3");
  const int uv0 =
      d.accessor(bytesOf(std::vector<float>{0.5f, 0.25f, 1, 0, 0, 1}), kFloat, 3, "VEC2");
  const int uv1 = d.accessor(bytesOf(std::vector<uint8_t>{255, 0, 0, 255, 51, 102, 0, 0}), kUByte,
                             3, "VEC2", ",\"normalized\":true");
  const int rgba = d.accessor(
      bytesOf(std::vector<uint16_t>{65535, 0, 0, 65535, 0, 65535, 0, 0, 0, 0, 65535, 65535}),
      kUShort, 3, "VEC4", ",\"normalized\":true");
  const int rgb =
      d.accessor(bytesOf(std::vector<float>{0.1f, 0.2f, 0.3f, 0.4f, 0.5f, 0.6f, 0.7f, 0.8f, 0.9f}),
                 kFloat, 3, "VEC3");
  const std::string plain = "{\"attributes\":{\"POSITION\":" + std::to_string(pos) + "}}";
  const std::string rich = "{\"attributes\":{\"POSITION\":" + std::to_string(pos) +
                           ",\"TEXCOORD_0\":" + std::to_string(uv0) +
                           ",\"TEXCOORD_1\":" + std::to_string(uv1) +
                           ",\"COLOR_0\":" + std::to_string(rgba) + "}}";
  const std::string rgb_only = "{\"attributes\":{\"POSITION\":" + std::to_string(pos) +
                               ",\"COLOR_0\":" + std::to_string(rgb) + "}}";
  // A triangle without, one with everything, one with COLOR_0 alone, one without again.
  const Scene s = load(d.json(meshScene(plain + "," + rich + "," + rgb_only + "," + plain)));
  ASSERT_EQ(s.triangleCount(), 4u);
  ASSERT_EQ(s.texcoords[0].size(), 12u);
  ASSERT_EQ(s.texcoords[1].size(), 12u);
  ASSERT_EQ(s.colors.size(), 12u);
  for (int v = 0; v < 3; ++v) {
    EXPECT_EQ(s.texcoords[0][v], glm::vec2(0.0f));  // before the first primitive with them
    EXPECT_EQ(s.colors[v], glm::vec4(1.0f));
    EXPECT_EQ(s.texcoords[0][9 + v], glm::vec2(0.0f));  // after
    EXPECT_EQ(s.colors[9 + v], glm::vec4(1.0f));
  }
  EXPECT_EQ(s.texcoords[0][3], glm::vec2(0.5f, 0.25f));
  EXPECT_EQ(s.texcoords[1][3], glm::vec2(1.0f, 0.0f));
  EXPECT_EQ(s.texcoords[1][5], glm::vec2(0.2f, 0.4f));  // 51/255, 102/255
  EXPECT_EQ(s.colors[3], glm::vec4(1, 0, 0, 1));
  EXPECT_EQ(s.colors[5], glm::vec4(0, 0, 1, 1));
  EXPECT_EQ(s.texcoords[0][6], glm::vec2(0.0f));              // the COLOR_0-only primitive
  EXPECT_EQ(s.colors[7], glm::vec4(0.4f, 0.5f, 0.6f, 1.0f));  // VEC3: alpha 1
}

TEST(GltfTextures, AMirroringNodeSwapsTheAttributesWithTheVertices) {
  Document d;
  const int pos = d.accessor(bytesOf(kTriangle), kFloat, 3, "VEC3");
  const int uv = d.accessor(bytesOf(std::vector<float>{0, 0, 1, 0, 0, 1}), kFloat, 3, "VEC2");
  std::string json = d.json(meshScene("{\"attributes\":{\"POSITION\":" + std::to_string(pos) +
                                      ",\"TEXCOORD_0\":" + std::to_string(uv) + "}}"));
  json.replace(json.find("{\"mesh\":0}"), 10, "{\"mesh\":0,\"scale\":[-1,1,1]}");
  const Scene s = load(json);
  // Vertices 1 and 2 swap to keep the winding; their texture coordinates follow them.
  EXPECT_EQ(s.positions[1], glm::vec3(0, 1, 0));
  EXPECT_EQ(s.texcoords[0][1], glm::vec2(0, 1));
  EXPECT_EQ(s.texcoords[0][2], glm::vec2(1, 0));
}

TEST(GltfTextures, WrongAttributeTypesAreErrors) {
  Document d;
  const int pos = d.accessor(bytesOf(kTriangle), kFloat, 3, "VEC3");
  const int bytes = d.accessor(std::string(12, '\1'), kByte, 3, "VEC4");
  const int vec3 = d.accessor(bytesOf(kTriangle), kFloat, 3, "VEC3");
  const int short_uv = d.accessor(bytesOf(std::vector<float>{0, 0, 1, 0}), kFloat, 2, "VEC2");
  auto prim = [&](const std::string& attribute, int accessor) {
    return d.json(meshScene("{\"attributes\":{\"POSITION\":" + std::to_string(pos) + ",\"" +
                            attribute + "\":" + std::to_string(accessor) + "}}"));
  };
  EXPECT_NE(errorOf(prim("COLOR_0", bytes)).find("COLOR_0 must be VEC3 or VEC4"),
            std::string::npos);
  EXPECT_NE(errorOf(prim("TEXCOORD_0", vec3)).find("TEXCOORD_0 must be VEC2"), std::string::npos);
  EXPECT_NE(errorOf(prim("TEXCOORD_1", short_uv)).find("TEXCOORD_1 has 2 elements for 3 vertices"),
            std::string::npos);
}

}  // namespace
}  // namespace gridrt
