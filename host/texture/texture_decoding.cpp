#include "texture_decoding.h"

#include <optional>

#include "errors.h"
#include "image_decoding.h"
#include "mip_levels.h"
#include "parallel_loops.h"

namespace gridrt {
namespace {

// What the materials read image i for.
struct ImageUse {
  bool colour = false, data = false;
};

std::vector<ImageUse> imageUses(const Scene& scene) {
  std::vector<ImageUse> uses(scene.images.size());
  auto mark = [&](const TextureSlot& slot, bool colour) {
    if (!slot.used()) return;
    const int image = scene.textures[size_t(slot.texture)].image;
    if (image < 0) return;
    (colour ? uses[size_t(image)].colour : uses[size_t(image)].data) = true;
  };
  for (const Material& m : scene.materials) {
    mark(m.base_color_texture, true);
    mark(m.emissive_texture, true);
    mark(m.metallic_roughness_texture, false);
    mark(m.occlusion_texture, false);
    mark(m.normal_texture, false);
  }
  return uses;
}

// RGBA texels of a decoded image; `srgb`: RGB through the inverse sRGB transfer.
TexelLevel texelsOf(const ImageData& image, bool srgb) {
  TexelLevel level;
  level.width = image.width;
  level.height = image.height;
  level.texels.resize(size_t(image.width) * size_t(image.height));
  const int channels = image.channels;
  const long long count = (long long)level.texels.size();
  parallelFor(0LL, (long long)(count), [&](long long t) {
    const float* px = &image.pixels[size_t(t) * size_t(channels)];
    glm::vec4 v(1.0f);
    if (channels <= 2) {
      v = glm::vec4(glm::vec3(px[0]), channels == 2 ? px[1] : 1.0f);
    } else {
      v = glm::vec4(px[0], px[1], px[2], channels >= 4 ? px[3] : 1.0f);
    }
    if (srgb)
      for (int c = 0; c < 3; ++c) v[c] = srgbToLinear(v[c]);
    level.texels[size_t(t)] = v;
  });
  return level;
}

}  // namespace

void decodeTextures(Scene& scene) {
  const std::vector<ImageUse> uses = imageUses(scene);
  for (size_t i = 0; i < scene.images.size(); ++i) {
    if (!uses[i].colour && !uses[i].data) continue;
    SceneImage& image = scene.images[i];
    std::optional<ImageData> decoded;
    try {
      decoded = decodeImage(image.encoded, image.mime_type.empty() ? image.uri : image.mime_type,
                            image.name + (image.uri.empty() ? "" : " ('" + image.uri + "')"));
    } catch (const RenderError& e) {
      std::string warning = std::string(e.what()) + "; its textures are ignored";
      for (char& c : warning)
        if (c == '\n' || c == '\r') c = ' ';  // image names come from the file
      scene.warnings.push_back(warning);
      continue;
    }
    if (uses[i].colour) image.colour = withMipLevels(texelsOf(*decoded, true));
    if (uses[i].data) image.data = withMipLevels(texelsOf(*decoded, false));
  }
}

}  // namespace gridrt
