#include "scene_triangles.h"

#include <cmath>
#include <string>

namespace gridrt {
namespace {

// Any unit vector serves a zero-area triangle, which is never shaded from a real hit.
const glm::vec3 kArbitraryNormal{0.0f, 0.0f, 1.0f};

}  // namespace

bool isFinite(const glm::vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

glm::vec3 unitOr(const glm::dvec3& v, const glm::vec3& fallback) {
  const double len = glm::length(v);
  if (!(len > 0.0) || !std::isfinite(len)) return fallback;
  glm::vec3 u(v / len);
  return isFinite(u) ? u : fallback;
}

glm::vec3 geometricNormal(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c) {
  return unitOr(glm::cross(glm::dvec3(b - a), glm::dvec3(c - a)), kArbitraryNormal);
}

TriangleVerdict triangleVerdict(const glm::vec3 (&p)[3]) {
  if (!isFinite(p[0]) || !isFinite(p[1]) || !isFinite(p[2])) return TriangleVerdict::Degenerate;
  const glm::dvec3 a(p[0]);
  if (glm::cross(glm::dvec3(p[1]) - a, glm::dvec3(p[2]) - a) == glm::dvec3(0.0))
    return TriangleVerdict::ZeroArea;
  return TriangleVerdict::Kept;
}

bool countVerdict(TriangleVerdict verdict, Scene& scene) {
  if (verdict == TriangleVerdict::Degenerate) ++scene.dropped_degenerate;
  if (verdict == TriangleVerdict::ZeroArea) ++scene.dropped_zero_area;
  return verdict == TriangleVerdict::Kept;
}

bool keepTriangle(const glm::vec3 (&p)[3], Scene& scene) {
  return countVerdict(triangleVerdict(p), scene);
}

void triangleCorners(const glm::vec3 (&p)[3], const glm::vec3 (&n)[3], glm::vec3* positions,
                     glm::vec3* normals) {
  const glm::vec3 face = geometricNormal(p[0], p[1], p[2]);
  for (int k = 0; k < 3; ++k) {
    positions[k] = p[k];
    normals[k] = n[k] == glm::vec3(0.0f) ? face : n[k];
  }
}

void addTriangle(const glm::vec3 (&p)[3], const glm::vec3 (&n)[3], int material, Scene& scene) {
  glm::vec3 positions[3], normals[3];
  triangleCorners(p, n, positions, normals);
  scene.positions.insert(scene.positions.end(), positions, positions + 3);
  scene.normals.insert(scene.normals.end(), normals, normals + 3);
  scene.material_of.push_back(material);
}

void finishNormals(bool any_normals, Scene& scene) {
  if (!any_normals) scene.normals.clear();
}

void addDropWarnings(Scene& scene) {
  if (scene.skipped_primitives > 0)
    scene.warnings.push_back(std::to_string(scene.skipped_primitives) +
                             " primitive(s) skipped (points, lines, strips, fans or no "
                             "positions)");
  if (scene.dropped_degenerate > 0)
    scene.warnings.push_back(std::to_string(scene.dropped_degenerate) +
                             " triangle(s) with NaN/Inf coordinates dropped");
  if (scene.dropped_zero_area > 0)
    scene.warnings.push_back(std::to_string(scene.dropped_zero_area) +
                             " triangle(s) with zero area dropped");
}

}  // namespace gridrt
