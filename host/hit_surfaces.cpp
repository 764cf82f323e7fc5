#include "hit_surfaces.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace gridrt {

namespace {

constexpr int L = kSurfaceLanes;

// GLM's dot product of two vec3s, (x + y) + z.
inline float dot3(float ax, float ay, float az, float bx, float by, float bz) {
  return ax * bx + ay * by + az * bz;
}

}  // namespace

std::vector<ShadingTriangle> makeShadingTriangles(const Scene& scene,
                                                  const std::vector<glm::vec3>& geometric_normals) {
  std::vector<ShadingTriangle> out(scene.triangleCount());
  const bool smooth = !scene.normals.empty();
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
    s.n0 = smooth ? scene.normals[3 * i] : glm::vec3(0.0f);
    s.n1 = smooth ? scene.normals[3 * i + 1] : glm::vec3(0.0f);
    s.n2 = smooth ? scene.normals[3 * i + 2] : glm::vec3(0.0f);
    s.geometric = geometric_normals[i];
  }
  return out;
}

void computeSurfaces(const ShadingTriangle* triangles, bool smooth, SurfaceLanes& s) {
  // The triangles' data gathered into lanes first, so the arithmetic below is plain
  // lane loops.
  alignas(64) float v0x[L], v0y[L], v0z[L], e1x[L], e1y[L], e1z[L], e2x[L], e2y[L], e2z[L];
  alignas(64) float d11[L], d12[L], d22[L], det[L];
  alignas(64) float n0x[L], n0y[L], n0z[L], n1x[L], n1y[L], n1z[L], n2x[L], n2y[L], n2z[L];
  for (int k = 0; k < L; ++k) {
    const ShadingTriangle& tri = triangles[s.tri[k]];
    v0x[k] = tri.v0.x, v0y[k] = tri.v0.y, v0z[k] = tri.v0.z;
    e1x[k] = tri.e1.x, e1y[k] = tri.e1.y, e1z[k] = tri.e1.z;
    e2x[k] = tri.e2.x, e2y[k] = tri.e2.y, e2z[k] = tri.e2.z;
    d11[k] = tri.d11, d12[k] = tri.d12, d22[k] = tri.d22, det[k] = tri.det;
    n0x[k] = tri.n0.x, n0y[k] = tri.n0.y, n0z[k] = tri.n0.z;
    n1x[k] = tri.n1.x, n1y[k] = tri.n1.y, n1z[k] = tri.n1.z;
    n2x[k] = tri.n2.x, n2y[k] = tri.n2.y, n2z[k] = tri.n2.z;
    s.gx[k] = tri.geometric.x, s.gy[k] = tri.geometric.y, s.gz[k] = tri.geometric.z;
  }
#pragma omp simd
  for (int k = 0; k < L; ++k) {
    const float px = s.ox[k] + s.t[k] * s.dx[k];
    const float py = s.oy[k] + s.t[k] * s.dy[k];
    const float pz = s.oz[k] + s.t[k] * s.dz[k];
    s.px[k] = px, s.py[k] = py, s.pz[k] = pz;
    float nx = s.gx[k], ny = s.gy[k], nz = s.gz[k];
    if (smooth) {
      // Barycentrics of p in the file's vertex order (the kernels' u, v refer to the
      // canonical order of prepareTriangles); a degenerate triangle weighs all three alike.
      const float wx = px - v0x[k], wy = py - v0y[k], wz = pz - v0z[k];
      const float w1 = dot3(wx, wy, wz, e1x[k], e1y[k], e1z[k]);
      const float w2 = dot3(wx, wy, wz, e2x[k], e2y[k], e2z[k]);
      const bool solid = det[k] > 0.0f;
      const float b1 = solid ? (d22[k] * w1 - d12[k] * w2) / det[k] : 1.0f / 3.0f;
      const float b2 = solid ? (d11[k] * w2 - d12[k] * w1) / det[k] : 1.0f / 3.0f;
      const float b0 = solid ? 1.0f - b1 - b2 : 1.0f / 3.0f;
      const float sx = b0 * n0x[k] + b1 * n1x[k] + b2 * n2x[k];
      const float sy = b0 * n0y[k] + b1 * n1y[k] + b2 * n2y[k];
      const float sz = b0 * n0z[k] + b1 * n1z[k] + b2 * n2z[k];
      const float len = std::sqrt(dot3(sx, sy, sz, sx, sy, sz));
      if (len > 0.0f) nx = sx / len, ny = sy / len, nz = sz / len;
    }
    const bool backface = dot3(s.gx[k], s.gy[k], s.gz[k], s.dx[k], s.dy[k], s.dz[k]) > 0.0f;
    if (backface) s.gx[k] = -s.gx[k], s.gy[k] = -s.gy[k], s.gz[k] = -s.gz[k];
    if (dot3(nx, ny, nz, s.gx[k], s.gy[k], s.gz[k]) < 0.0f) nx = -nx, ny = -ny, nz = -nz;
    s.nx[k] = nx, s.ny[k] = ny, s.nz[k] = nz;
    s.backface[k] = backface;
  }
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
    const float cos_outer = std::cos(light.outer_cone), cos_inner = std::cos(light.inner_cone);
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
