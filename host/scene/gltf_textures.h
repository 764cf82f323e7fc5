// glTF images, samplers, textures and a material's texture slots -> Scene (scene.h).
//
// - Images: the encoded bytes of a buffer view (its range checked against its buffer), a
//   data URI or an external file (read through the loader's guarded file access, so only
//   inside the scene's folder). Nothing is decoded here: decodeTextures (host/texture)
//   does that before rendering. An image tinygltf could not read (a missing file) stays
//   without bytes; its textures then look up nothing, with a warning when decoded.
// - Samplers: wrapS/wrapT (REPEAT, CLAMP_TO_EDGE, MIRRORED_REPEAT), magFilter and
//   minFilter (NEAREST or LINEAR; the *_MIPMAP_* minification filters read mip levels,
//   NEAREST and LINEAR read level 0 only); no sampler: repeat, linear, mip-mapped.
// - Texture slots (textureInfo): the texture, TEXCOORD_0 or _1, and KHR_texture_transform
//   (offset, rotation, scale, texCoord) as the affine map in TextureSlot.
// - A texture without a source (e.g. one that only names KHR_texture_basisu) is ignored
//   with a warning; the textures of material extensions too, and alphaMode MASK and
//   BLEND (drawn opaque).
// Indices out of range (texture, source, sampler, buffer view) are SceneErrors naming the
// element; a texCoord other than 0 or 1 is a warning and the slot is ignored.
#pragma once
#include <tiny_gltf.h>

#include <string>
#include <vector>

#include "scene.h"

namespace gridrt::gltf {

// tinygltf's image callback: keeps a URI image's encoded bytes in Image::image (as_is)
// instead of decoding them. Buffer-view images are left to convertImages, which checks
// the view's range first (tinygltf hands the callback an unchecked pointer).
bool keepEncodedImage(tinygltf::Image* image, int image_index, std::string* err, std::string* warn,
                      int width, int height, const unsigned char* bytes, int size, void* user);

// Scene::images and Scene::textures from the model's images, textures and samplers.
void convertTextures(const tinygltf::Model& model, const std::string& label, Scene& scene);

// The texture slots of material `m` (material `index`) into `out`; warnings for what is
// ignored are appended to `warnings`.
void convertMaterialTextures(const tinygltf::Model& model, const tinygltf::Material& m,
                             size_t index, const std::string& label, Material& out,
                             std::vector<std::string>& warnings);

}  // namespace gridrt::gltf
