#include "camera_rays.h"

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <limits>

#include "parallel_loops.h"

namespace gridrt {

Camera defaultCamera(const Bounds& bounds) {
  Camera c;
  c.name = "default";
  glm::vec3 center = bounds.center();
  float radius = 0.5f * glm::length(bounds.extent());
  if (!(radius > 0.0f)) radius = 1.0f;
  float distance = radius / std::sin(c.yfov * 0.5f);
  const glm::vec3 towards_eye(std::sin(kDefaultAzimuth) * std::cos(kDefaultElevation),
                              std::sin(kDefaultElevation),
                              std::cos(kDefaultAzimuth) * std::cos(kDefaultElevation));
  glm::vec3 eye = center + distance * towards_eye;
  c.world = glm::inverse(glm::lookAt(eye, center, glm::vec3(0, 1, 0)));
  return c;
}

Camera lookAtCamera(const glm::vec3& eye, const glm::vec3& target, float yfov) {
  Camera c;
  c.name = "look-at";
  c.yfov = yfov;
  glm::vec3 forward = glm::normalize(target - eye);
  glm::vec3 up = std::fabs(forward.y) > 0.999f ? glm::vec3(0, 0, 1) : glm::vec3(0, 1, 0);
  c.world = glm::inverse(glm::lookAt(eye, target, up));
  return c;
}

CameraRayGenerator::CameraRayGenerator(const Camera& camera, int width, int height)
    : camera_(camera),
      width_(float(width)),
      height_(float(height)),
      aspect_(float(width) / float(height)),
      tan_half_(std::tan(camera.yfov * 0.5f)),
      origin_(camera.world[3]) {}

void CameraRayGenerator::centreRow(int j, int i0, int i1, GrRay* out, float* out_dx, float* out_dy,
                                   float* out_dz) const {
  if (camera_.orthographic) {
    for (int i = i0; i < i1; ++i) {
      const GrRay ray = (*this)(i, j, 0.5f, 0.5f);
      out[i - i0] = ray;
      if (out_dx) out_dx[i - i0] = ray.dx, out_dy[i - i0] = ray.dy, out_dz[i - i0] = ray.dz;
    }
    return;
  }
  // operator()'s arithmetic spelled out in glm's order of operations: normalize(v) is
  // v * (1 / sqrt((x*x + y*y) + z*z)); M * v is (M0*x + M1*y) + (M2*z + M3*w).
  const glm::mat4& m = camera_.world;
  const float y = 1.0f - 2.0f * (float(j) + 0.5f) / height_;
  const float ay = y * tan_half_, az = -1.0f;
  constexpr int kChunk = 64;
  float dx[kChunk], dy[kChunk], dz[kChunk];
  for (int c0 = i0; c0 < i1; c0 += kChunk) {
    const int count = std::min(kChunk, i1 - c0);
    for (int k = 0; k < count; ++k) {
      const float x = 2.0f * (float(c0 + k) + 0.5f) / width_ - 1.0f;
      const float ax = x * tan_half_ * aspect_;
      const float inv = 1.0f / std::sqrt((ax * ax + ay * ay) + az * az);
      const float nx = ax * inv, ny = ay * inv, nz = az * inv;
      const float wx = (m[0][0] * nx + m[1][0] * ny) + (m[2][0] * nz + m[3][0] * 0.0f);
      const float wy = (m[0][1] * nx + m[1][1] * ny) + (m[2][1] * nz + m[3][1] * 0.0f);
      const float wz = (m[0][2] * nx + m[1][2] * ny) + (m[2][2] * nz + m[3][2] * 0.0f);
      const float inv2 = 1.0f / std::sqrt((wx * wx + wy * wy) + wz * wz);
      dx[k] = wx * inv2;
      dy[k] = wy * inv2;
      dz[k] = wz * inv2;
    }
    for (int k = 0; k < count; ++k)
      out[c0 - i0 + k] =
          GrRay{origin_.x, origin_.y, origin_.z, 0.0f,
                dx[k],     dy[k],     dz[k],     std::numeric_limits<float>::infinity()};
    if (out_dx)
      for (int k = 0; k < count; ++k) {
        out_dx[c0 - i0 + k] = dx[k];
        out_dy[c0 - i0 + k] = dy[k];
        out_dz[c0 - i0 + k] = dz[k];
      }
  }
}

void CameraRayGenerator::centreWindow(const PixelWindow& window, GrRay* out) const {
  parallelFor(int(window.y0), int(window.y1), [&](int y) {
    centreRow(y, window.x0, window.x1, out + size_t(y - window.y0) * window.width());
  });
}

Bounds primaryRayOrigins(const Camera& camera, int width, int height) {
  Bounds b;
  if (!camera.orthographic) {
    b.grow(glm::vec3(camera.world[3]));
    return b;
  }
  // The image rectangle's corners, (i, j) = (0 or width, 0 or height) at offset 0: each
  // origin coordinate is a rounded sum of rounded products, monotone in the pixel's x
  // and in its y, so the corners bound every origin, rounding included.
  const CameraRayGenerator rays(camera, width, height);
  for (int j : {0, height})
    for (int i : {0, width}) {
      const GrRay r = rays(i, j, 0.0f, 0.0f);
      b.grow(glm::vec3(r.ox, r.oy, r.oz));
    }
  return b;
}

GrRay cameraRay(const Camera& camera, int width, int height, int i, int j, float sx, float sy) {
  return CameraRayGenerator(camera, width, height)(i, j, sx, sy);
}

void jitter(uint32_t pixel, uint32_t sample, float& sx, float& sy) {
  // PCG-style hash of (pixel, sample): cheap, deterministic, well spread.
  auto hash = [](uint32_t v) {
    v = v * 747796405u + 2891336453u;
    v = ((v >> ((v >> 28u) + 4u)) ^ v) * 277803737u;
    return (v >> 22u) ^ v;
  };
  uint32_t a = hash(pixel * 9781u + sample * 6271u + 1u);
  uint32_t b = hash(a ^ 0x9e3779b9u);
  sx = float(a >> 8) * (1.0f / 16777216.0f);
  sy = float(b >> 8) * (1.0f / 16777216.0f);
}

}  // namespace gridrt
