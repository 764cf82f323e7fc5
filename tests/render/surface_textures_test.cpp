// Textures and vertex colours at the hits the renderer shades, read back from the albedo
// AOV: a unit quad seen face-on by an orthographic camera whose N x N pixel centres fall
// on known texture coordinates, (u, v) = ((i + 0.5) / N, (j + 0.5) / N) for pixel (i, j).
// The expected values are computed here from the texels, one pixel at a time.
#include <gtest/gtest.h>

#include <cmath>
#include <glm/glm.hpp>
#include <vector>

#include "default_scene.h"
#include "reference_intersector.h"
#include "renderer.h"
#include "texture_sampling.h"

namespace gridrt {
namespace {

// Texture coordinates interpolated in float from the hit point stray by a few ulps of 1;
// a blend of texels moves by at most that times the texels' difference (< 1): 1e-5 is
// ten times the largest seen, and far below a texel step (1/15 here).
constexpr float kInterpolationTolerance = 1e-5f;

constexpr int kTexels = 4;  // the texture is kTexels x kTexels

// Texel (column c, row r): every texel another colour.
glm::vec4 texelColour(int c, int r) {
  return {float(c) / 3.0f, float(r) / 3.0f, float(c + 4 * r) / 15.0f, 1.0f};
}

TexelLevel testLevel(int size, glm::vec4 (*colour)(int, int)) {
  TexelLevel level;
  level.width = level.height = size;
  for (int r = 0; r < size; ++r)
    for (int c = 0; c < size; ++c) level.texels.push_back(colour(c, r));
  return level;
}

// The unit quad [0,1]^2 at z = 0 facing +z, textured with texture 0 through `slot`;
// TEXCOORD_0 = (x, 1 - y) * uv_scale, TEXCOORD_1 = (1 - x, 1 - y).
Scene texturedQuad(const TextureSlot& slot, float uv_scale = 1.0f) {
  Scene scene;
  Material m;
  m.base_color = {0.5f, 1.0f, 0.25f};
  m.base_color_texture = slot;
  const int material = shapes::addMaterial(scene, m);
  shapes::addRect(scene, {0.5f, 0.5f, 0.0f}, {0.5f, 0.0f, 0.0f}, {0.0f, 0.5f, 0.0f}, material);
  for (const glm::vec3& p : scene.positions) {
    scene.texcoords[0].push_back(glm::vec2(p.x, 1.0f - p.y) * uv_scale);
    scene.texcoords[1].push_back(glm::vec2(1.0f - p.x, 1.0f - p.y));
  }
  SceneImage image;
  image.colour.levels.push_back(testLevel(kTexels, texelColour));
  scene.images.push_back(image);
  Texture texture;
  texture.image = 0;
  texture.mag_filter = texture.min_filter = TextureFilter::Nearest;
  scene.textures.push_back(texture);
  // No light reaches it: the albedo AOV does not depend on lighting anyway.
  scene.lights.push_back(Light{});
  scene.lights.back().intensity = 0.0f;
  scene.has_lights = true;
  return scene;
}

TextureSlot slot0() {
  TextureSlot slot;
  slot.texture = 0;
  return slot;
}

// The albedo AOV of an n x n render of `scene` (rgb per pixel, row 0 at the top).
std::vector<glm::vec3> albedoOf(const Scene& scene, int n) {
  Camera camera;
  camera.orthographic = true;
  camera.xmag = camera.ymag = 0.5f;
  camera.world = shapes::lookAtWorld({0.5f, 0.5f, 2.0f}, {0.5f, 0.5f, 0.0f});
  ReferenceIntersector reference(scene);
  RenderSettings settings;
  settings.width = settings.height = n;
  settings.max_depth = 1;
  settings.want_aovs = true;
  Renderer renderer(scene, camera, reference, settings);
  Frame frame;
  renderer.render(frame);
  std::vector<glm::vec3> out(size_t(n) * n);
  for (size_t p = 0; p < out.size(); ++p)
    out[p] = {frame.aovs.albedo[3 * p], frame.aovs.albedo[3 * p + 1], frame.aovs.albedo[3 * p + 2]};
  return out;
}

const glm::vec3 kFactor(0.5f, 1.0f, 0.25f);

// Every pixel of an n x n render: the albedo against expected(i, j) times the factor.
template <typename Expected>
void expectAlbedo(const std::vector<glm::vec3>& albedo, int n, const Expected& expected,
                  float tolerance = 0.0f) {
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const glm::vec3 want = kFactor * glm::vec3(expected(i, j));
      const glm::vec3 got = albedo[size_t(j) * n + i];
      for (int c = 0; c < 3; ++c)
        ASSERT_NEAR(got[c], want[c], tolerance) << "pixel " << i << "," << j << " channel " << c;
    }
}

TEST(SurfaceTextures, AlbedoIsTheFactorTimesTheTexelUnderEachPixel) {
  expectAlbedo(albedoOf(texturedQuad(slot0()), kTexels), kTexels,
               [](int i, int j) { return texelColour(i, j); });
}

TEST(SurfaceTextures, TheSecondUvSetIsReadWhereTheSlotSaysSo) {
  TextureSlot slot = slot0();
  slot.texcoord = 1;  // (1 - x, 1 - y): mirrored left to right
  expectAlbedo(albedoOf(texturedQuad(slot), kTexels), kTexels,
               [](int i, int j) { return texelColour(kTexels - 1 - i, j); });
}

// Texture coordinates 0..2 over 8 pixels: pixel i reads texel i of an endless row, wrapped.
int wrapped(int i, TextureWrap wrap) {
  if (wrap == TextureWrap::Repeat) return i % kTexels;
  if (wrap == TextureWrap::ClampToEdge) return std::min(i, kTexels - 1);
  return i < kTexels ? i : 2 * kTexels - 1 - i;
}

TEST(SurfaceTextures, WrapModesRepeatMirrorAndClampEachAxis) {
  const TextureWrap modes[] = {TextureWrap::Repeat, TextureWrap::MirroredRepeat,
                               TextureWrap::ClampToEdge};
  for (int k = 0; k < 3; ++k) {
    const TextureWrap s = modes[k], t = modes[(k + 1) % 3];
    Scene scene = texturedQuad(slot0(), 2.0f);
    scene.textures[0].wrap_s = s;
    scene.textures[0].wrap_t = t;
    SCOPED_TRACE(k);
    expectAlbedo(albedoOf(scene, 2 * kTexels), 2 * kTexels,
                 [&](int i, int j) { return texelColour(wrapped(i, s), wrapped(j, t)); });
  }
}

TEST(SurfaceTextures, LinearFilteringBlendsTheFourNearestTexels) {
  Scene scene = texturedQuad(slot0());
  scene.textures[0].mag_filter = TextureFilter::Linear;  // 8 pixels on 4 texels: magnified
  const int n = 2 * kTexels;
  auto texel = [](int c, int r) {
    return texelColour((c + kTexels) % kTexels, (r + kTexels) % kTexels);  // repeat
  };
  // Pixel i's centre lies at texel coordinate (i + 0.5) / 2 - 0.5 = i / 2 - 0.25.
  expectAlbedo(
      albedoOf(scene, n), n,
      [&](int i, int j) {
        const double x = i / 2.0 - 0.25, y = j / 2.0 - 0.25;
        const int c = int(std::floor(x)), r = int(std::floor(y));
        const float a = float(x - c), b = float(y - r);
        return (1 - b) * ((1 - a) * texel(c, r) + a * texel(c + 1, r)) +
               b * ((1 - a) * texel(c, r + 1) + a * texel(c + 1, r + 1));
      },
      kInterpolationTolerance);
}

TEST(SurfaceTextures, TheTextureTransformMapsTheCoordinatesFirst) {
  TextureSlot slot = slot0();
  // A quarter turn of the coordinates, (u, v) -> (-v, u), applied before the lookup.
  slot.map_u = {0.0f, -1.0f, 0.0f};
  slot.map_v = {1.0f, 0.0f, 0.0f};
  expectAlbedo(albedoOf(texturedQuad(slot), kTexels), kTexels,
               [](int i, int j) { return texelColour(kTexels - 1 - j, i); });
}

TEST(SurfaceTextures, VertexColoursMultiplyTheBaseColour) {
  Scene scene = texturedQuad(TextureSlot{});  // no texture
  // A colour linear in the position: interpolating it is exact at every point.
  for (const glm::vec3& p : scene.positions) scene.colors.push_back({p.x, p.y, 0.5f, 1.0f});
  const int n = kTexels;
  expectAlbedo(
      albedoOf(scene, n), n,
      [&](int i, int j) { return glm::vec4((i + 0.5f) / n, 1.0f - (j + 0.5f) / n, 0.5f, 1.0f); },
      kInterpolationTolerance);
}

// A texture four times finer than the pixels: the footprint of a pixel covers 2 x 2
// texels of the 8 x 8 level, so the lookup reads level 1, whose texels here have
// another colour than level 0's; without mip-maps it reads level 0.
TEST(SurfaceTextures, AMinifiedTextureReadsTheMipLevelOfItsFootprint) {
  Scene scene = texturedQuad(slot0());
  TexelImage& image = scene.images[0].colour;
  const glm::vec4 fine(1.0f), coarse(0.25f, 0.5f, 0.75f, 1.0f), coarser(0.0f);
  image.levels.clear();
  for (int size = 8; size >= 1; size /= 2) {
    TexelLevel level;
    level.width = level.height = size;
    const glm::vec4 colour = size == 8 ? fine : size == 4 ? coarse : coarser;
    level.texels.assign(size_t(size) * size, colour);
    image.levels.push_back(level);
  }
  // lod = log2(pixel width / cos) + 0.5 log2(uv area / area) + 0.5 log2(8 * 8)
  //     = log2(1/4) + 0 + 3 = 1.
  expectAlbedo(albedoOf(scene, kTexels), kTexels, [&](int, int) { return coarse; });
  scene.textures[0].mipmaps = false;
  expectAlbedo(albedoOf(scene, kTexels), kTexels, [&](int, int) { return fine; });
}

// Textures are looked up for every generation of rays: a camera looks at a mirror turned
// 45 degrees, which reflects every camera ray (along -z) to +x, onto a quad whose emissive
// texture is all that lights it. Pixel (i, j) of the mirror shows texel (3 - i, j).
TEST(SurfaceTextures, AMirrorShowsTheTextureItReflects) {
  Scene scene;
  Material mirror;
  mirror.base_color = glm::vec3(1.0f);
  mirror.metallic = 1.0f;
  mirror.roughness = 0.0f;  // all mirror, no Lambert lobe
  Material lamp;
  lamp.base_color = glm::vec3(0.0f);
  lamp.roughness = 1.0f;  // neither diffuse nor specular: its emission alone
  lamp.emissive = glm::vec3(1.0f);
  lamp.emissive_texture = slot0();
  shapes::addRect(scene, {0, 0, 0}, {0.5f, 0, -0.5f}, {0, 0.5f, 0},
                  shapes::addMaterial(scene, mirror));
  shapes::addRect(scene, {2, 0, 0}, {0, 0, 0.5f}, {0, 0.5f, 0}, shapes::addMaterial(scene, lamp));
  // The mirror's triangles take no texture; the lamp's (u, v) = (z + 0.5, 0.5 - y).
  for (const glm::vec3& p : scene.positions) scene.texcoords[0].push_back({p.z + 0.5f, 0.5f - p.y});
  SceneImage image;
  image.colour.levels.push_back(testLevel(kTexels, texelColour));
  scene.images.push_back(image);
  Texture texture;
  texture.image = 0;
  texture.mag_filter = texture.min_filter = TextureFilter::Nearest;
  scene.textures.push_back(texture);
  scene.lights.push_back(Light{});
  scene.lights.back().intensity = 0.0f;
  scene.has_lights = true;

  Camera camera;
  camera.orthographic = true;
  camera.xmag = camera.ymag = 0.5f;
  camera.world = shapes::lookAtWorld({0, 0, 5}, {0, 0, 0});
  ReferenceIntersector reference(scene);
  RenderSettings settings;
  settings.width = settings.height = kTexels;
  settings.max_depth = 1;
  Renderer renderer(scene, camera, reference, settings);
  Frame frame;
  renderer.render(frame);
  for (int j = 0; j < kTexels; ++j)
    for (int i = 0; i < kTexels; ++i)
      for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(frame.film.rgb[size_t(3 * (j * kTexels + i) + c)],
                    texelColour(kTexels - 1 - i, j)[c], kInterpolationTolerance)
            << "pixel " << i << "," << j;
}

// A normal map of one texel on the quad (normal +z): its tangent-space normal (x, y, z) =
// 2 rgb - 1 turned into the tangent frame: computed from the texture coordinates (T = +x
// along u, B = +y, the image's up), or from TANGENT. The shading normal AOV shows it, and
// a light straight above (irradiance pi, a white Lambert surface) gives kd (ambient + n.z).
TEST(SurfaceTextures, NormalMapsTurnTheShadingNormalInTheTangentFrame) {
  const glm::vec3 tangent_space(0.5f, 0.25f, 0.8f);
  struct Case {
    float scale;
    std::vector<glm::vec4> tangents;
    glm::vec3 expected;
  };
  const Case cases[] = {
      {1.0f, {}, {0.5f, 0.25f, 0.8f}},
      {2.0f, {}, {1.0f, 0.5f, 0.8f}},
      // T = +y, w = -1: B = -cross(+z, +y) = +x.
      {1.0f, std::vector<glm::vec4>(6, glm::vec4(0, 1, 0, -1)), {0.25f, 0.5f, 0.8f}},
  };
  for (const Case& c : cases) {
    Scene scene = texturedQuad(TextureSlot{});
    Material& m = scene.materials[0];
    m.normal_texture = slot0();
    m.normal_scale = c.scale;
    m.roughness = 1.0f;  // Lambert alone
    scene.tangents = c.tangents;
    TexelLevel texel;
    texel.width = texel.height = 1;
    texel.texels = {glm::vec4((tangent_space + 1.0f) * 0.5f, 1.0f)};
    scene.images[0].data.levels = {texel};
    scene.lights[0].type = LightType::Directional;
    scene.lights[0].intensity = 3.14159265f;
    Camera camera;
    camera.orthographic = true;
    camera.xmag = camera.ymag = 0.5f;
    camera.world = shapes::lookAtWorld({0.5f, 0.5f, 2.0f}, {0.5f, 0.5f, 0.0f});
    ReferenceIntersector reference(scene);
    RenderSettings settings;
    settings.width = settings.height = 4;
    Renderer renderer(scene, camera, reference, settings);
    Frame frame;
    renderer.render(frame);
    const glm::vec3 want = glm::normalize(c.expected);
    SCOPED_TRACE(c.scale);
    for (size_t p = 0; p < 16; ++p)
      for (int ch = 0; ch < 3; ++ch) {
        ASSERT_NEAR(frame.aovs.shading_normal[3 * p + ch], want[ch], kInterpolationTolerance);
        ASSERT_NEAR(frame.film.rgb[3 * p + ch], kFactor[ch] * (settings.ambient + want.z),
                    kInterpolationTolerance);
      }
  }
}

TEST(SurfaceTextures, ShadingNormalAovIsTheInterpolatedNormalBesideTheGeometricOne) {
  Scene scene = texturedQuad(TextureSlot{});
  const glm::vec3 tilted(0.0f, 0.6f, 0.8f);
  for (glm::vec3& n : scene.normals) n = tilted;
  Camera camera;
  camera.orthographic = true;
  camera.xmag = camera.ymag = 0.5f;
  camera.world = shapes::lookAtWorld({0.5f, 0.5f, 2.0f}, {0.5f, 0.5f, 0.0f});
  ReferenceIntersector reference(scene);
  RenderSettings settings;
  settings.width = settings.height = 4;
  Renderer renderer(scene, camera, reference, settings);
  Frame frame;
  renderer.render(frame);
  for (size_t p = 0; p < 16; ++p)
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(frame.aovs.shading_normal[3 * p + c], tilted[c], kInterpolationTolerance);
      EXPECT_EQ(frame.aovs.normal[3 * p + c], c == 2 ? 1.0f : 0.0f);
    }
}

}  // namespace
}  // namespace gridrt
