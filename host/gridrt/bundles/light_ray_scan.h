// The light bundles' passes over each ray of a batch towards a light (light_bundles.h).
// The first finds each ray's cube face, its point on that face and its origin's depth, the
// faces' windows, and what light culling needs of the batch; the second, each ray's cell.
// scanLightRay is the definition, one ray at a time; scanLightRays makes the same values a vector
// of rays at a time (Highway, the build's static target), bit for bit: the same IEEE operations in
// the same order (tests/gridrt/bundles/light_ray_scan_test.cpp). The one-ray pass took ~8 ns of a
// core a ray, five times what reading the rays and writing its outputs take.
#pragma once
#include <array>
#include <cmath>
#include <cstddef>
#include <glm/glm.hpp>

#include "gridrt_types.h"
#include "light_bundles.h"

namespace gridrt {

// What one slice of the pass gathers besides its per-ray outputs.
struct LightRayScan {
  float miss_squared = 0.0f;  // the largest squared distance of a float end from the light
                              // (infinite where one is not finite)
  float reach = 0.0f;         // the largest |o|_1 + |tmax| (infinite where not finite)
  float min_length_squared = INFINITY;  // the smallest |d|^2 (0 for a NaN)
  std::array<FaceWindow, 6> windows{};  // the face points of the slice's rays, by face
};

// The squared distance of the float end o + tmax * d of `ray` from `light` (glm::length's
// square; missOfLight's).
float endToLightSquared(const GrRay& ray, const glm::vec3& light);

// Ray `ray` seen from `light`: its face (the face of -d; face 0 for a ray without a
// direction), its point (u, v) on it (0, 0 without a direction) and originDepth, added to
// `scan`.
void scanLightRay(const GrRay& ray, const glm::vec3& light, int& face, float& u, float& v,
                  double& depth, LightRayScan& scan);

// scanLightRay for rays [first, last), writing face_of[r], uv[2 r], uv[2 r + 1] and
// depth[r] of each ray r.
void scanLightRays(const GrRay* rays, size_t first, size_t last, const glm::vec3& light,
                   int* face_of, float* uv, double* depth, LightRayScan& scan);

// The second pass, once the faces' cells are laid out: cell_of[r] =
// faces[face_of[r]].cellOf(uv[2 r], uv[2 r + 1]) for rays [first, last), a vector of rays
// at a time, bit for bit.
void cellsOfLightRays(const std::array<FaceWindow, 6>& faces, const int* face_of, const float* uv,
                      size_t first, size_t last, int* cell_of);

}  // namespace gridrt
