#include "surface_textures.h"

#include <cmath>

#include "texture_sampling.h"

namespace gridrt {
namespace {

// A triangle without uv area (or world area) has no footprint to measure: -infinity, so
// its lookups read the finest level.
float halfLog2Ratio(float uv_area, float world_area) {
  const float ratio = world_area > 0.0f ? uv_area / world_area : 0.0f;
  return ratio > 0.0f && std::isfinite(ratio) ? 0.5f * std::log2(ratio) : -INFINITY;
}

}  // namespace

SurfaceTextures::SurfaceTextures(const Scene& scene) : scene_(scene) {
  bool any = !scene.colors.empty();
  for (const Material& m : scene.materials) any = any || m.textured();
  if (!any) return;
  triangles_.resize(scene.triangleCount());
  for (size_t i = 0; i < triangles_.size(); ++i) {
    const glm::vec3* v = &scene.positions[3 * i];
    Triangle& t = triangles_[i];
    t.v0 = v[0];
    t.e1 = v[1] - v[0];
    t.e2 = v[2] - v[0];
    t.d11 = glm::dot(t.e1, t.e1);
    t.d12 = glm::dot(t.e1, t.e2);
    t.d22 = glm::dot(t.e2, t.e2);
    t.det = t.d11 * t.d22 - t.d12 * t.d12;
    const float world_area = 0.5f * glm::length(glm::cross(t.e1, t.e2));
    for (int set = 0; set < 2; ++set) {
      const std::vector<glm::vec2>& uv = scene.texcoords[set];
      float uv_area = 0.0f;
      if (!uv.empty()) {
        const glm::vec2 a = uv[3 * i + 1] - uv[3 * i], b = uv[3 * i + 2] - uv[3 * i];
        uv_area = 0.5f * std::fabs(a.x * b.y - a.y * b.x);
      }
      t.uv_density[set] = halfLog2Ratio(uv_area, world_area);
    }
  }
}

glm::vec3 SurfaceTextures::barycentrics(int tri, const glm::vec3& p) const {
  const Triangle& t = triangles_[size_t(tri)];
  if (!(t.det > 0.0f)) return glm::vec3(1.0f / 3.0f);
  const glm::vec3 w = p - t.v0;
  const float w1 = glm::dot(w, t.e1), w2 = glm::dot(w, t.e2);
  const float b1 = (t.d22 * w1 - t.d12 * w2) / t.det;
  const float b2 = (t.d11 * w2 - t.d12 * w1) / t.det;
  return glm::vec3(1.0f - b1 - b2, b1, b2);
}

glm::vec4 SurfaceTextures::vertexColour(int tri, const glm::vec3& b) const {
  if (scene_.colors.empty()) return glm::vec4(1.0f);
  const size_t v = 3 * size_t(tri);
  return b.x * scene_.colors[v] + b.y * scene_.colors[v + 1] + b.z * scene_.colors[v + 2];
}

glm::vec4 SurfaceTextures::lookup(const TextureSlot& slot, bool colour, int tri, const glm::vec3& b,
                                  float footprint_log2) const {
  const glm::vec4 none(1.0f);
  if (!slot.used()) return none;
  const Texture& texture = scene_.textures[size_t(slot.texture)];
  if (texture.image < 0) return none;
  const SceneImage& image = scene_.images[size_t(texture.image)];
  const TexelImage& texels = colour ? image.colour : image.data;
  if (texels.empty()) return none;
  const std::vector<glm::vec2>& uvs = scene_.texcoords[slot.texcoord];
  glm::vec2 uv(0.0f);
  if (!uvs.empty()) {
    const size_t v = 3 * size_t(tri);
    uv = b.x * uvs[v] + b.y * uvs[v + 1] + b.z * uvs[v + 2];
  }
  const glm::vec3 h(uv, 1.0f);
  const glm::vec2 mapped(glm::dot(slot.map_u, h), glm::dot(slot.map_v, h));
  const TexelLevel& base = texels.levels[0];
  const float det = std::fabs(slot.map_u.x * slot.map_v.y - slot.map_u.y * slot.map_v.x);
  const float lod = footprint_log2 + triangles_[size_t(tri)].uv_density[slot.texcoord] +
                    0.5f * std::log2(float(base.width) * float(base.height) * det);
  return sampleTexture(texels, texture, mapped, std::isnan(lod) ? 0.0f : lod);
}

glm::vec4 SurfaceTextures::tangentAt(int tri, const glm::vec3& b, const glm::vec3& n,
                                     int set) const {
  const size_t v = 3 * size_t(tri);
  if (!scene_.tangents.empty() && scene_.tangents[v] != glm::vec4(0.0f)) {
    const glm::vec4* t = &scene_.tangents[v];
    const glm::vec3 sum = b.x * glm::vec3(t[0]) + b.y * glm::vec3(t[1]) + b.z * glm::vec3(t[2]);
    return glm::vec4(sum, t[0].w);
  }
  const std::vector<glm::vec2>& uv = scene_.texcoords[set];
  if (uv.empty()) return glm::vec4(0.0f);
  const Triangle& t = triangles_[size_t(tri)];
  const glm::vec2 d1 = uv[v + 1] - uv[v], d2 = uv[v + 2] - uv[v];
  const float det = d1.x * d2.y - d2.x * d1.y;
  if (!(std::fabs(det) > 0.0f)) return glm::vec4(0.0f);
  const glm::vec3 dpdu = (t.e1 * d2.y - t.e2 * d1.y) / det;
  const glm::vec3 dpdv = (t.e2 * d1.x - t.e1 * d2.x) / det;
  return glm::vec4(dpdu, glm::dot(glm::cross(n, dpdu), dpdv) > 0.0f ? -1.0f : 1.0f);
}

glm::vec3 SurfaceTextures::mappedNormal(int tri, const glm::vec3& p, const glm::vec3& n,
                                        bool backface, float footprint, float cos_theta) const {
  const Material& m = scene_.materials[size_t(scene_.material_of[size_t(tri)])];
  const TextureSlot& slot = m.normal_texture;
  const Texture& texture = scene_.textures[size_t(slot.texture)];
  if (texture.image < 0 || scene_.images[size_t(texture.image)].data.empty()) return n;
  const glm::vec3 front = backface ? -n : n;
  const glm::vec3 b = barycentrics(tri, p);
  const glm::vec4 tangent = tangentAt(tri, b, front, slot.texcoord);
  const glm::vec3 t = glm::vec3(tangent) - front * glm::dot(front, glm::vec3(tangent));
  const float t_length = glm::length(t);
  if (tangent.w == 0.0f || !(t_length > 0.0f) || !std::isfinite(t_length)) return n;
  const glm::vec3 unit_t = t / t_length;
  const glm::vec3 bitangent = glm::cross(front, unit_t) * tangent.w;
  const float cosine = std::fabs(cos_theta);
  const float footprint_log2 =
      footprint > 0.0f && cosine > 0.0f ? std::log2(footprint / cosine) : -INFINITY;
  const glm::vec3 texel = glm::vec3(lookup(slot, false, tri, b, footprint_log2)) * 2.0f - 1.0f;
  const glm::vec3 mapped = unit_t * (texel.x * m.normal_scale) +
                           bitangent * (texel.y * m.normal_scale) + front * texel.z;
  const float length = glm::length(mapped);
  if (!(length > 0.0f) || !std::isfinite(length)) return n;
  return (backface ? -mapped : mapped) / length;
}

MaterialSample SurfaceTextures::at(int tri, const glm::vec3& p, float footprint,
                                   float cos_theta) const {
  const Material& m = scene_.materials[size_t(scene_.material_of[size_t(tri)])];
  MaterialSample s{m.base_color, m.metallic, m.roughness, m.emissive, 1.0f};
  const glm::vec3 b = barycentrics(tri, p);
  s.base_color *= glm::vec3(vertexColour(tri, b));
  if (!m.textured()) return s;
  const float cosine = std::fabs(cos_theta);
  const float footprint_log2 =
      footprint > 0.0f && cosine > 0.0f ? std::log2(footprint / cosine) : -INFINITY;
  s.base_color *= glm::vec3(lookup(m.base_color_texture, true, tri, b, footprint_log2));
  const glm::vec4 mr = lookup(m.metallic_roughness_texture, false, tri, b, footprint_log2);
  s.roughness *= mr.g;
  s.metallic *= mr.b;
  s.emissive *= glm::vec3(lookup(m.emissive_texture, true, tri, b, footprint_log2));
  if (m.occlusion_texture.used()) {
    const float ao = lookup(m.occlusion_texture, false, tri, b, footprint_log2).r;
    s.occlusion = 1.0f + m.occlusion_strength * (ao - 1.0f);
  }
  return s;
}

float SurfaceTextures::alphaAt(int tri, const glm::vec3& p) const {
  const Material& m = scene_.materials[size_t(scene_.material_of[size_t(tri)])];
  float alpha = m.base_alpha;
  if (!varies(scene_.material_of[size_t(tri)])) return alpha;
  const glm::vec3 b = barycentrics(tri, p);
  alpha *= vertexColour(tri, b).a;
  if (m.base_color_texture.used()) alpha *= lookup(m.base_color_texture, true, tri, b, -INFINITY).a;
  return alpha;
}

}  // namespace gridrt
