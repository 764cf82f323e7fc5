// A material's values at a hit point: its factors times its textures (looked up at the
// hit's interpolated, transformed texture coordinates) times the interpolated vertex
// colour. The renderer asks only for the materials that vary across their triangles
// (varies()); every other hit keeps its material's own terms, as before textures.
//
// Levels of detail follow ray cones (Akenine-Moeller et al., "Texture Level of Detail
// Strategies for Real-Time Ray Tracing", Ray Tracing Gems, ch. 20): a ray's footprint
// has a world-space width w at the hit, and the lookup reads the mip level
//   lod = log2(w / |cos theta|) + 0.5 log2(uv area / world area of the triangle)
//         + 0.5 log2(texels of the image) + 0.5 log2(|det| of KHR_texture_transform).
#pragma once
#include <glm/glm.hpp>
#include <vector>

#include "scene.h"

namespace gridrt {

// The varying values of a material at one hit.
struct MaterialSample {
  glm::vec3 base_color;  // baseColorFactor x texture x COLOR_0 (linear)
  float metallic, roughness;
  glm::vec3 emissive;
  float occlusion;  // 1 + strength (texture R - 1); 1 without an occlusion texture
};

class SurfaceTextures {
 public:
  // Keeps a reference to `scene` (its images decoded or not: an image without texels
  // looks up nothing, the factors alone apply).
  explicit SurfaceTextures(const Scene& scene);

  // Whether hits on `material` need at(): it has a texture or the scene vertex colours.
  bool varies(int material) const {
    return !scene_.colors.empty() || scene_.materials[size_t(material)].textured();
  }

  // The material of triangle `tri` at its point p; footprint: the ray's width there (0:
  // the finest level); cos_theta: the cosine between the ray and the surface normal.
  MaterialSample at(int tri, const glm::vec3& p, float footprint, float cos_theta) const;

  // The alpha of triangle `tri` at its point p: baseColorFactor's alpha x the base colour
  // texture's alpha (its finest level: a cut-out's edge does not move with distance) x the
  // interpolated COLOR_0 alpha; what alphaMode MASK and BLEND read (docs/gltf.md, "Alpha").
  float alphaAt(int tri, const glm::vec3& p) const;

  // Whether hits on `material` have their shading normal from a normal map.
  bool hasNormalMap(int material) const {
    return scene_.materials[size_t(material)].normal_texture.used();
  }

  // The shading normal n (unit, facing the ray; backface: the ray hit the back) at point p
  // of triangle `tri` turned by the material's normal map: the texel (2 rgb - 1, x and y
  // times normalTexture.scale) in the tangent frame (T, B, n). T is the interpolated
  // TANGENT, else the triangle's dP/du; T made orthogonal to n; B = cross(n, T) times the
  // tangent's w, else the sign that makes B point along -dP/dv (the image's up, glTF's
  // +Y). n itself when the frame or the texel is degenerate or the image not decoded.
  glm::vec3 mappedNormal(int tri, const glm::vec3& p, const glm::vec3& n, bool backface,
                         float footprint, float cos_theta) const;

  // The barycentric weights of p in triangle `tri` (vertices in the scene's order); a
  // degenerate triangle weighs its vertices alike.
  glm::vec3 barycentrics(int tri, const glm::vec3& p) const;

 private:
  struct Triangle {
    glm::vec3 v0, e1, e2;
    float d11, d12, d22, det;
    float uv_density[2];  // 0.5 log2(uv area / world area) per TEXCOORD set
  };
  // COLOR_0 at barycentrics b of `tri`; white when the scene has no vertex colours.
  glm::vec4 vertexColour(int tri, const glm::vec3& b) const;
  glm::vec4 lookup(const TextureSlot& slot, bool colour, int tri, const glm::vec3& b,
                   float footprint_log2) const;
  // The world tangent and the bitangent's sign at barycentrics b of `tri` (normal n, the
  // front side's), from TANGENT or from texture coordinate set `set`; w = 0 if none.
  glm::vec4 tangentAt(int tri, const glm::vec3& b, const glm::vec3& n, int set) const;

  const Scene& scene_;
  std::vector<Triangle> triangles_;  // empty when no material varies
};

}  // namespace gridrt
