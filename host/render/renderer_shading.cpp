// The shading passes: headlight shading of the paper's measurement, Whitted shading of a
// generation's hits (plain hits 16 at a time, the rest one by one) in chunks on all cores,
// their shadow and spawned rays gathered in chunk order.
#include <algorithm>
#include <cmath>
#include <limits>

#include "bounds.h"
#include "parallel_loops.h"
#include "phong_highlights.h"
#include "prefault.h"
#include "prepared_triangles.h"
#include "renderer.h"
#include "stopwatch.h"

namespace gridrt {

namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();

GrRay makeRay(const glm::vec3& o, const glm::vec3& d, float tmax, float tmin = 0.0f) {
  return GrRay{o.x, o.y, o.z, tmin, d.x, d.y, d.z, tmax};
}

glm::vec3 reflectDirection(const glm::vec3& d, const glm::vec3& n) {
  return d - 2.0f * glm::dot(d, n) * n;
}

// The next free index of two parallel vectors whose first `count` elements are in use
// (both grown when full): the shading loop writes its outputs in place, and its buffers
// keep their sizes between frames.
template <typename A, typename B>
size_t nextSlot(std::vector<A>& a, std::vector<B>& b, size_t& count) {
  if (count == a.size()) {
    a.resize(std::max<size_t>(256, 2 * count));
    b.resize(a.size());
  }
  return count++;
}

}  // namespace

Renderer::PrimarySurface Renderer::primarySurface(const GrHit& hit, const GrRay& ray,
                                                  const ShadingTriangle* smooth_triangles) const {
  const HitSurface h = surfaceOfHit(smooth_triangles, geometric_normals_.data(), hit.prim, ray.ox,
                                    ray.oy, ray.oz, ray.dx, ray.dy, ray.dz, hit.t);
  const int material = scene_.material_of[hit.prim];
  const glm::vec3 d(ray.dx, ray.dy, ray.dz);
  const glm::vec3 n = mappedNormal(h, hit, d, cone_origin_);
  const glm::vec3 base = surface_textures_.varies(material)
                             ? surface_textures_
                                   .at(hit.prim, glm::vec3(h.px, h.py, h.pz),
                                       coneWidth(cone_origin_, hit.t), glm::dot(n, d))
                                   .base_color
                             : scene_.materials[material].base_color;
  return {n, base};
}

glm::vec3 Renderer::mappedNormal(const HitSurface& h, const GrHit& hit, const glm::vec3& d,
                                 float cone) const {
  const glm::vec3 n(h.nx, h.ny, h.nz);
  if (!surface_textures_.hasNormalMap(scene_.material_of[hit.prim])) return n;
  return surface_textures_.mappedNormal(hit.prim, glm::vec3(h.px, h.py, h.pz), n, h.backface,
                                        coneWidth(cone, hit.t), glm::dot(n, d));
}

void Renderer::applyNormalMap(SurfaceLanes& lanes, int k, float cone) const {
  const glm::vec3 n(lanes.nx[k], lanes.ny[k], lanes.nz[k]);
  const glm::vec3 d(lanes.dx[k], lanes.dy[k], lanes.dz[k]);
  const glm::vec3 mapped = surface_textures_.mappedNormal(
      lanes.tri[k], glm::vec3(lanes.px[k], lanes.py[k], lanes.pz[k]), n, lanes.backface[k] != 0,
      coneWidth(cone, lanes.t[k]), glm::dot(n, d));
  lanes.nx[k] = mapped.x, lanes.ny[k] = mapped.y, lanes.nz[k] = mapped.z;
}

bool Renderer::worthTracing(const glm::vec3& weight) const {
  return std::max({weight.x, weight.y, weight.z}) >= settings_.min_path_weight;
}

size_t Renderer::shadeGeneration(int depth, const std::vector<GrRay>& rays,
                                 const std::vector<PathRay>* paths, PrimaryPaths primary,
                                 size_t shadow_offset, Frame& frame) {
  return settings_.primary_only ? shadeHeadlight(depth, rays, primary, shadow_offset, frame)
                                : shadeWhitted(depth, rays, paths, primary, shadow_offset, frame);
}

size_t Renderer::shadeHeadlight(int depth, const std::vector<GrRay>& rays, PrimaryPaths primary,
                                size_t shadow_offset, Frame& frame) {
  Stopwatch clock;
  const size_t n = rays.size();
  Generation& g = generations_[depth];
  resizeFaultedIn(g.radiance, n);
  std::vector<glm::vec3>& local = g.radiance;
  // Null without vertex normals (hit_surfaces.h).
  const ShadingTriangle* smooth_triangles =
      shading_triangles_.empty() ? nullptr : shading_triangles_.data();
  // The primary generation only, in ray order, in slices of kShadeChunkRays: a miss is
  // shaded at once, the hits 16 at a time, their surfaces in lanes (computeSurfaces) and
  // |n . d| in lanes; base colours and normal maps, which only some materials have, hit by
  // hit. Every value is primarySurface's, bit for bit (HeadlightShading.*).
  // With one sample a pixel (pixels distinct, in ray order), each ray's radiance goes
  // straight into its pixel: the same addition addPassRadiance would make, a pass less.
  const glm::vec3 weight(primary.weight);
  const glm::vec3 background = weight * settings_.background;
  const bool into_pixels = primary.spp == 1;
  g.radiance_in_pixels = into_pixels;
  auto store = [&](size_t i, const glm::vec3& value) {
    if (into_pixels)
      radiance_.add(window_pixels_[i], value);
    else
      local[i] = value;
  };
  const long long chunks = (long long)((n + kShadeChunkRays - 1) / kShadeChunkRays);
  // Handed out dynamically: the hits, which cost most, crowd where the model is.
  parallelForDynamic(0LL, chunks, 1LL, [&](long long chunk) {
    SurfaceLanes lanes;
    size_t block_ray[kSurfaceLanes];
    alignas(64) float br[kSurfaceLanes], bg[kSurfaceLanes], bb[kSurfaceLanes];
    alignas(64) float cosine[kSurfaceLanes];
    auto shadeBlock = [&](int count) {
      lanes.padFrom(count);
      computeSurfaces(smooth_triangles, geometric_normals_.data(), lanes);
      for (int k = 0; k < count; ++k) {
        // primarySurface's normal map and base colour, written out: a call with the hit's
        // point, normal and direction built for it cost ~10 % of this shading.
        const int material = scene_.material_of[lanes.tri[k]];
        if (surface_textures_.hasNormalMap(material)) applyNormalMap(lanes, k, cone_origin_);
        glm::vec3 base = scene_.materials[material].base_color;
        if (surface_textures_.varies(material)) {
          const glm::vec3 n(lanes.nx[k], lanes.ny[k], lanes.nz[k]);
          const glm::vec3 d(lanes.dx[k], lanes.dy[k], lanes.dz[k]);
          base = surface_textures_
                     .at(lanes.tri[k], glm::vec3(lanes.px[k], lanes.py[k], lanes.pz[k]),
                         coneWidth(cone_origin_, lanes.t[k]), glm::dot(n, d))
                     .base_color;
        }
        br[k] = weight.x * base.x, bg[k] = weight.y * base.y, bb[k] = weight.z * base.z;
      }
#pragma omp simd
      for (int k = 0; k < kSurfaceLanes; ++k)
        cosine[k] = std::fabs(
            dot3(lanes.nx[k], lanes.ny[k], lanes.nz[k], lanes.dx[k], lanes.dy[k], lanes.dz[k]));
      for (int k = 0; k < count; ++k)
        store(block_ray[k], glm::vec3(br[k] * cosine[k], bg[k] * cosine[k], bb[k] * cosine[k]));
    };
    const size_t begin = size_t(chunk) * kShadeChunkRays;
    const size_t end = std::min(n, begin + kShadeChunkRays);
    int count = 0;
    for (size_t i = begin; i < end; ++i) {
      const GrHit& hit = g.hits[i];
      if (hit.prim < 0) {
        store(i, background);
        continue;
      }
      const int k = count++;
      block_ray[k] = i;
      lanes.setHit(k, rays[i], hit);
      if (count == kSurfaceLanes) shadeBlock(count), count = 0;
    }
    if (count > 0) shadeBlock(count);
  });
  frame.times.shade_ms += clock.ms();
  g.first_shadow = shadow_offset;
  g.shadow_count = 0;
  generations_[depth + 1].rays.clear();
  generations_[depth + 1].paths.clear();
  return 0;
}

size_t Renderer::shadeWhitted(int depth, const std::vector<GrRay>& rays,
                              const std::vector<PathRay>* paths, PrimaryPaths primary,
                              size_t shadow_offset, Frame& frame) {
  Stopwatch clock;
  const size_t n = rays.size();
  // Each chunk writes its own outputs (Spawned), which keeps the parallel loop free of
  // shared appends; they are concatenated afterwards in chunk order, the shading order.
  Generation& g = generations_[depth];
  resizeFaultedIn(g.radiance, n);
  std::vector<glm::vec3>& local = g.radiance;
  // Null without vertex normals (hit_surfaces.h).
  const ShadingTriangle* smooth_triangles =
      shading_triangles_.empty() ? nullptr : shading_triangles_.data();
  g.radiance_in_pixels = false;
  const bool spawn = depth < settings_.max_depth;
  // Chunks handed out dynamically: the rays' cost varies across the image (background,
  // walls, mirror and glass), so a static split leaves one core waiting.
  const size_t chunks = (n + kShadeChunkRays - 1) / kShadeChunkRays;
  if (spawned_.size() < chunks) spawned_.resize(chunks);

  parallelForDynamic(0LL, (long long)(chunks), 1LL, [&](long long chunk) {
    Spawned& out = spawned_[chunk];
    out.shadow_count = 0;
    out.ray_count = 0;
    out.light_lanes.resize(lights_.size());
    SurfaceLanes lanes;
    // The plain path (plain_shading.h) needs the highlights of Phong shading.
    const bool plain_path = settings_.plain_lanes && settings_.shading == ShadingModel::Phong;
    if (plain_path) out.plain_light_lanes.resize(lights_.size());
    PlainLanes plain;
    SpawnLanes spawned;
    const size_t chunk_begin = size_t(chunk) * kShadeChunkRays;
    const size_t chunk_end = std::min(n, chunk_begin + kShadeChunkRays);
    // The primary generation in its shading order: sample `sample` of the pixel at
    // `position` of the order (j / spp and j % spp, counted along instead of divided).
    const size_t spp = size_t(primary.spp);
    size_t position = chunk_begin / spp, sample = chunk_begin % spp;
    // The hits in blocks of 16 (a miss is done at once): their surfaces and light
    // directions in lanes, then each hit's shading in order.
    size_t block_ray[kSurfaceLanes];
    PathRay block_path[kSurfaceLanes];
    for (size_t j = chunk_begin; j < chunk_end;) {
      int count = 0;
      for (; count < kSurfaceLanes && j < chunk_end; ++j) {
        const size_t pixel_index = paths           ? 0
                                   : primary.order ? size_t(primary.order[position])
                                                   : position;
        const size_t i = paths || !primary.order ? j : pixel_index * spp + sample;
        sample = sample + 1 == spp ? 0 : sample + 1;
        position += sample == 0;
        const GrHit& hit = g.hits[i];
        if (hit.prim < 0) {
          local[i] =
              (paths ? (*paths)[i].weight : glm::vec3(primary.weight)) * settings_.background;
          continue;
        }
        const GrRay& ray = rays[i];
        const int k = count++;
        block_ray[k] = i;
        // Field by field: a path built in a temporary and copied out (a 16-byte load of
        // narrower stores, a store-forwarding stall) held 8 % of the shading's samples.
        PathRay& path = block_path[k];
        if (paths) {
          path = (*paths)[i];
        } else {
          path.pixel = window_pixels_[pixel_index];
          path.weight = glm::vec3(primary.weight);
          path.kind = RayKind::Primary;
          path.cone = cone_origin_;
        }
        lanes.setHit(k, ray, hit);
      }
      if (count == 0) continue;
      lanes.padFrom(count);
      computeSurfaces(smooth_triangles, geometric_normals_.data(), lanes);
      for (int k = 0; k < count; ++k)  // normal maps turn the shading normal before the lights
        if (surface_textures_.hasNormalMap(scene_.material_of[lanes.tri[k]]))
          applyNormalMap(lanes, k, block_path[k].cone);
      for (size_t l = 0; l < lights_.size(); ++l)
        computeLightLanes(lights_[l], lanes, out.light_lanes[l]);
      if (settings_.shading == ShadingModel::Phong) {
        // The highlights for each material's own exponent; a textured one's is made below.
        alignas(64) float exponent[kSurfaceLanes];
        for (int k = 0; k < kSurfaceLanes; ++k)
          exponent[k] = material_terms_[scene_.material_of[lanes.tri[k]]].phong_exponent;
        for (size_t l = 0; l < lights_.size(); ++l)
          computeHighlights(lanes, exponent, out.light_lanes[l]);
      }
      bool spawning = false;  // a plain lane of the block mirrors or transmits
      if (plain_path) {
        for (int k = 0; k < kSurfaceLanes; ++k) {
          const glm::vec3& w = block_path[k < count ? k : 0].weight;
          plain.wr[k] = w.x, plain.wg[k] = w.y, plain.wb[k] = w.z;
          plain.material[k] = scene_.material_of[lanes.tri[k]];
          spawning |= plain_materials_[plain.material[k]].spawning != 0;
        }
        computePlainLanes(lanes, plain_materials_.data(), settings_.ambient, settings_.ray_offset,
                          plain);
        spawning &= spawn;
        if (spawning)
          computeSpawnLanes(lanes, plain_materials_.data(), settings_.ray_offset,
                            settings_.min_path_weight, plain, spawned);
        for (size_t l = 0; l < lights_.size(); ++l)
          computePlainLight(plain, plain_materials_.data(), out.light_lanes[l],
                            out.plain_light_lanes[l]);
      }
      for (int k = 0; k < count; ++k) {
        const size_t i = block_ray[k];
        const PathRay& path = block_path[k];
        if (plain_path && plain.plain[k]) {
          local[i] = glm::vec3(plain.lr[k], plain.lg[k], plain.lb[k]);
          for (size_t l = 0; l < lights_.size(); ++l) {
            const PlainLightLanes& c = out.plain_light_lanes[l];
            if (!c.emit[k]) continue;
            const LightLanes& light = out.light_lanes[l];
            const size_t s = nextSlot(out.shadow_rays, out.shadows, out.shadow_count);
            out.shadow_rays[s] = makeRay(glm::vec3(plain.ax[k], plain.ay[k], plain.az[k]),
                                         glm::vec3(light.lx[k], light.ly[k], light.lz[k]),
                                         light.distance[k], plain.offset[k]);
            out.shadows[s] = ShadowRay{path.pixel, int(l), glm::vec3(c.cr[k], c.cg[k], c.cb[k])};
          }
          if (!spawning) continue;
          const float cone = coneWidth(path.cone, lanes.t[k]);
          auto spawnRay = [&](float ox, float oy, float oz, float dx, float dy, float dz, float wr,
                              float wg, float wb, RayKind kind) {
            const size_t s = nextSlot(out.rays, out.paths, out.ray_count);
            out.rays[s] = makeRay(glm::vec3(ox, oy, oz), glm::vec3(dx, dy, dz), kInf);
            out.paths[s] = PathRay{path.pixel, glm::vec3(wr, wg, wb), kind, cone};
          };
          const SpawnLanes& o = spawned;  // the refraction ray first, as below
          if (o.refract[k])
            spawnRay(o.rox[k], o.roy[k], o.roz[k], o.rdx[k], o.rdy[k], o.rdz[k], o.rwr[k], o.rwg[k],
                     o.rwb[k], RayKind::Refraction);
          if (o.reflect[k])
            spawnRay(plain.ax[k], plain.ay[k], plain.az[k], o.fdx[k], o.fdy[k], o.fdz[k], o.fwr[k],
                     o.fwg[k], o.fwb[k], RayKind::Reflection);
          continue;
        }
        const GrHit& hit = g.hits[i];
        glm::vec3 d(lanes.dx[k], lanes.dy[k], lanes.dz[k]);
        const int tri = hit.prim;
        const int material = scene_.material_of[tri];
        const Material& mat = scene_.materials[material];
        glm::vec3 weight = path.weight;
        const glm::vec3 p(lanes.px[k], lanes.py[k], lanes.pz[k]);
        const glm::vec3 ng(lanes.gx[k], lanes.gy[k], lanes.gz[k]);
        const glm::vec3 n(lanes.nx[k], lanes.ny[k], lanes.nz[k]);
        const bool backface = lanes.backface[k];
        // Textures and vertex colours: the material's values at this hit.
        const float cone = coneWidth(path.cone, hit.t);
        SurfaceTerms terms = material_terms_[material];
        glm::vec3 base_color = mat.base_color, emissive = mat.emissive;
        float metallic = mat.metallic, roughness = mat.roughness;
        float ambient = settings_.ambient;
        if (surface_textures_.varies(material)) {
          const MaterialSample here = surface_textures_.at(tri, p, cone, glm::dot(n, d));
          terms = surfaceTerms(mat, here.base_color, here.metallic, here.roughness);
          base_color = here.base_color;
          metallic = here.metallic;
          roughness = here.roughness;
          emissive = here.emissive;
          ambient *= here.occlusion;
        }
        // Beer-Lambert absorption inside a transmissive volume (KHR_materials_volume).
        if (backface && mat.transmission > 0.0f && mat.attenuation_distance > 0.0f)
          weight *= glm::pow(glm::max(mat.attenuation_color, glm::vec3(1e-6f)),
                             glm::vec3(hit.t / mat.attenuation_distance));
        // BLEND: the alpha's share of the light is the surface's, the rest goes on along
        // the ray (from the same origin past this hit) as a straight transmission.
        if (mat.alpha_mode == AlphaMode::Blend) {
          const float coverage = see_through_.coverage(rays[i], hit);
          const glm::vec3 through = weight * (1.0f - coverage);
          if (spawn && coverage < 1.0f && worthTracing(through)) {
            const size_t s = nextSlot(out.rays, out.paths, out.ray_count);
            out.rays[s] = rays[i];
            out.rays[s].tmin = hit.t;
            out.paths[s] = PathRay{path.pixel, through, RayKind::Refraction, path.cone};
          }
          weight *= coverage;
        }
        local[i] = weight * (emissive + ambient * terms.diffuse);
        const glm::vec3 origin(lanes.ox[k], lanes.oy[k], lanes.oz[k]);
        // How far secondary origins leave the surface, and where shadow rays start.
        const float offset_distance = rayOffsetDistance(p, origin, settings_.ray_offset);
        glm::vec3 above = offsetRayOrigin(p, ng, offset_distance, settings_.ray_offset);
        for (size_t l = 0; l < lights_.size(); ++l) {
          const LightLanes& light = out.light_lanes[l];
          if (!light.lit[k]) continue;
          const glm::vec3 to_light(light.lx[k], light.ly[k], light.lz[k]);
          const glm::vec3 e(light.ex[k], light.ey[k], light.ez[k]);
          const float cos_theta = light.cos_theta[k];
          glm::vec3 direct;
          if (settings_.shading == ShadingModel::Gltf) {
            direct = gltfBrdf(base_color, metallic, roughness, n, -d, to_light, mat.transmission) *
                     e * cos_theta;
          } else {
            const float highlight = surface_textures_.varies(material)
                                        ? phongHighlight(light.rv[k], terms.phong_exponent)
                                        : light.highlight[k];
            direct = terms.diffuse / kPi * e * cos_theta + terms.specular * e * highlight;
          }
          glm::vec3 contribution = weight * direct;
          // glm::length(c) == 0 without its root (sqrt(x) == 0 exactly when x == 0).
          if (glm::dot(contribution, contribution) == 0.0f) continue;
          const size_t s = nextSlot(out.shadow_rays, out.shadows, out.shadow_count);
          out.shadow_rays[s] = makeRay(above, to_light, light.distance[k], offset_distance);
          out.shadows[s] = ShadowRay{path.pixel, int(l), contribution};
        }
        if (!spawn) continue;
        glm::vec3 reflect_weight = terms.mirror;
        if (terms.transmission > 0.0f) {
          float eta = backface ? mat.ior : 1.0f / mat.ior;
          float f = fresnelDielectric(-glm::dot(d, n), eta);
          glm::vec3 t_dir;
          glm::vec3 t_weight = weight * terms.transmission * (1.0f - f) * base_color;
          if (f < 1.0f && refractDirection(d, n, eta, t_dir) && glm::dot(t_dir, ng) < 0.0f) {
            if (worthTracing(t_weight)) {
              const size_t s = nextSlot(out.rays, out.paths, out.ray_count);
              out.rays[s] = makeRay(offsetRayOrigin(p, -ng, offset_distance, settings_.ray_offset),
                                    t_dir, kInf);
              out.paths[s] = PathRay{path.pixel, t_weight, RayKind::Refraction, cone};
            }
          } else {
            f = 1.0f;  // total internal reflection
          }
          reflect_weight += glm::vec3(terms.transmission * f);
        }
        if (glm::dot(reflect_weight, reflect_weight) > 0.0f &&
            worthTracing(weight * reflect_weight)) {
          glm::vec3 r = reflectDirection(d, n);
          if (glm::dot(r, ng) <= 0.0f) r = reflectDirection(d, ng);  // keep it above the surface
          const size_t s = nextSlot(out.rays, out.paths, out.ray_count);
          out.rays[s] = makeRay(above, r, kInf);
          out.paths[s] = PathRay{path.pixel, weight * reflect_weight, RayKind::Reflection, cone};
        }
      }
    }
  });
  frame.times.shade_ms += clock.ms();

  // The shadow rays after the earlier depths' (traced after the last depth).
  g.first_shadow = shadow_offset;
  g.shadow_count = concatenateChunks(chunks, &Spawned::shadow_rays, &Spawned::shadows,
                                     &Spawned::shadow_count, shadow_rays_, shadows_, shadow_offset);

  // The next generation: the spawned reflection and refraction rays, in chunk order.
  Generation& next = generations_[depth + 1];
  const size_t spawned = concatenateChunks(chunks, &Spawned::rays, &Spawned::paths,
                                           &Spawned::ray_count, next.rays, next.paths, 0);
  next.rays.resize(spawned);
  next.paths.resize(spawned);
  return g.shadow_count;
}

template <typename Extra>
size_t Renderer::concatenateChunks(size_t chunks, std::vector<GrRay> Spawned::*rays,
                                   std::vector<Extra> Spawned::*extras, size_t Spawned::*count,
                                   std::vector<GrRay>& all_rays, std::vector<Extra>& all_extras,
                                   size_t offset) {
  chunk_offsets_.assign(chunks + 1, offset);
  for (size_t c = 0; c < chunks; ++c)
    chunk_offsets_[c + 1] = chunk_offsets_[c] + spawned_[c].*count;
  if (all_rays.size() < chunk_offsets_[chunks]) resizeFaultedIn(all_rays, chunk_offsets_[chunks]);
  if (all_extras.size() < chunk_offsets_[chunks])
    resizeFaultedIn(all_extras, chunk_offsets_[chunks]);
  parallelFor(0LL, (long long)(chunks), [&](long long c) {
    const Spawned& out = spawned_[c];
    std::copy_n((out.*rays).begin(), out.*count, all_rays.begin() + chunk_offsets_[c]);
    std::copy_n((out.*extras).begin(), out.*count, all_extras.begin() + chunk_offsets_[c]);
  });
  return chunk_offsets_[chunks] - offset;
}

}  // namespace gridrt
