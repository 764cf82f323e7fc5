#include "hit_surfaces.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace gridrt {

namespace {

constexpr int L = kSurfaceLanes;

}  // namespace

std::vector<ShadingTriangle> makeShadingTriangles(const Scene& scene,
                                                  const std::vector<glm::vec3>& geometric_normals) {
  if (scene.normals.empty()) return {};
  std::vector<ShadingTriangle> out(scene.triangleCount());
  for (size_t i = 0; i < out.size(); ++i) {
    const glm::vec3* v = &scene.positions[3 * i];
    ShadingTriangle& s = out[i];
    s.v0 = v[0];
    s.e1 = v[1] - v[0];
    s.e2 = v[2] - v[0];
    s.d11 = glm::dot(s.e1, s.e1);
    s.d12 = glm::dot(s.e1, s.e2);
    s.d22 = glm::dot(s.e2, s.e2);
    s.det = s.d11 * s.d22 - s.d12 * s.d12;
    s.n0 = scene.normals[3 * i];
    s.n1 = scene.normals[3 * i + 1];
    s.n2 = scene.normals[3 * i + 2];
    s.geometric = geometric_normals[i];
  }
  return out;
}

namespace {

// surfaceAt in every lane: with vertex normals (the geometric normal from the shading
// triangle), or without (from g). The normals are read as floats: a lane loop gathers
// floats, not 12-byte structs.
void smoothSurfaceLanes(const ShadingTriangle* triangles, SurfaceLanes& s) {
#pragma omp simd
  for (int k = 0; k < L; ++k) {
    const ShadingTriangle& tri = triangles[s.tri[k]];
    const HitSurface h =
        surfaceAt<true>(&tri, glm::vec3(tri.geometric.x, tri.geometric.y, tri.geometric.z), s.ox[k],
                        s.oy[k], s.oz[k], s.dx[k], s.dy[k], s.dz[k], s.t[k]);
    s.px[k] = h.px, s.py[k] = h.py, s.pz[k] = h.pz;
    s.nx[k] = h.nx, s.ny[k] = h.ny, s.nz[k] = h.nz;
    s.gx[k] = h.gx, s.gy[k] = h.gy, s.gz[k] = h.gz;
    s.backface[k] = h.backface;
  }
}

void flatSurfaceLanes(const float* g, SurfaceLanes& s) {
#pragma omp simd
  for (int k = 0; k < L; ++k) {
    const int i = s.tri[k];
    const HitSurface h =
        surfaceAt<false>(nullptr, glm::vec3(g[3 * i], g[3 * i + 1], g[3 * i + 2]), s.ox[k], s.oy[k],
                         s.oz[k], s.dx[k], s.dy[k], s.dz[k], s.t[k]);
    s.px[k] = h.px, s.py[k] = h.py, s.pz[k] = h.pz;
    s.nx[k] = h.nx, s.ny[k] = h.ny, s.nz[k] = h.nz;
    s.gx[k] = h.gx, s.gy[k] = h.gy, s.gz[k] = h.gz;
    s.backface[k] = h.backface;
  }
}

}  // namespace

void computeSurfaces(const ShadingTriangle* triangles, const glm::vec3* geometric,
                     SurfaceLanes& s) {
  if (triangles)
    smoothSurfaceLanes(triangles, s);
  else
    flatSurfaceLanes(&geometric[0].x, s);
}

void computeLightLanes(const Light& light, const SurfaceLanes& s, LightLanes& out) {
  const glm::vec3 radiant = light.color * light.intensity;
  if (light.type == LightType::Directional) {
    const glm::vec3 to = -glm::normalize(light.direction);
    for (int k = 0; k < L; ++k) {
      out.lx[k] = to.x, out.ly[k] = to.y, out.lz[k] = to.z;
      out.distance[k] = std::numeric_limits<float>::infinity();
      out.ex[k] = radiant.x, out.ey[k] = radiant.y, out.ez[k] = radiant.z;
    }
  } else {
    // As lightIrradiance (whitted_shading.cpp): inverse square falloff, the range window,
    // the spot cone.
    const bool spot = light.type == LightType::Spot;
    // The cone's terms only for a spot (two std::cos calls a block cost more than the
    // block's arithmetic).
    const float cos_outer = spot ? std::cos(light.outer_cone) : 0.0f;
    const float cos_inner = spot ? std::cos(light.inner_cone) : 0.0f;
    const float cone_scale = 1.0f / std::max(1e-3f, cos_inner - cos_outer);
    const glm::vec3 axis = spot ? glm::normalize(light.direction) : glm::vec3(0.0f);
    alignas(64) float attenuation[L], r4[L];
    alignas(64) int away_from[L];
#pragma omp simd
    for (int k = 0; k < L; ++k) {
      const float vx = light.position.x - s.px[k], vy = light.position.y - s.py[k],
                  vz = light.position.z - s.pz[k];
      const float d2 = dot3(vx, vy, vz, vx, vy, vz);
      const float distance = std::sqrt(d2);
      const bool away = distance > 0.0f;  // else no direction and no irradiance
      away_from[k] = away;
      out.distance[k] = distance;
      out.lx[k] = away ? vx / distance : 0.0f;
      out.ly[k] = away ? vy / distance : 1.0f;
      out.lz[k] = away ? vz / distance : 0.0f;
      attenuation[k] = away ? 1.0f / d2 : 0.0f;
      const float r = distance / light.range;
      r4[k] = r * r * r * r;
    }
    if (light.range > 0.0f)  // std::pow has no vector form here: one call per lane
      for (int k = 0; k < L; ++k)
        attenuation[k] *= std::pow(std::clamp(1.0f - r4[k], 0.0f, 1.0f), 2.0f);
#pragma omp simd
    for (int k = 0; k < L; ++k) {
      float a = attenuation[k];
      if (spot) {
        const float cos_angle = dot3(-out.lx[k], -out.ly[k], -out.lz[k], axis.x, axis.y, axis.z);
        const float t = std::clamp((cos_angle - cos_outer) * cone_scale, 0.0f, 1.0f);
        a *= t * t;
      }
      out.ex[k] = away_from[k] ? radiant.x * a : 0.0f;
      out.ey[k] = away_from[k] ? radiant.y * a : 0.0f;
      out.ez[k] = away_from[k] ? radiant.z * a : 0.0f;
    }
  }
#pragma omp simd
  for (int k = 0; k < L; ++k) {
    const float cos_theta = dot3(s.nx[k], s.ny[k], s.nz[k], out.lx[k], out.ly[k], out.lz[k]);
    const float facing = dot3(s.gx[k], s.gy[k], s.gz[k], out.lx[k], out.ly[k], out.lz[k]);
    const float e2 = dot3(out.ex[k], out.ey[k], out.ez[k], out.ex[k], out.ey[k], out.ez[k]);
    out.cos_theta[k] = cos_theta;
    out.lit[k] = !(cos_theta <= 0.0f || facing <= 0.0f || std::sqrt(e2) == 0.0f);
  }
}

}  // namespace gridrt
