// Triangles in the form every intersector consumes (first vertex + two edges, GrTriangle),
// computed once per scene so all intersectors see bit-identical data.
#pragma once
#include <vector>

#include "bounds.h"
#include "gridrt_types.h"
#include "intersector.h"
#include "scene.h"

namespace gridrt {

// The three vertices in a canonical order (lexicographic): a triangle's t then does not
// depend on how the file ordered its vertices, so duplicate faces (the same three
// vertices, another order) get bit-identical hits and the tie rule (lower index) decides,
// as it does in the double-precision reference. Barycentrics therefore refer to this
// order; the renderer recomputes its own from the hit point.
void canonicalVertices(const glm::vec3* in, glm::vec3 out[3]);

// In the layout the kernels of `kernel` read: edges for Moeller-Trumbore, vertices for
// the watertight test; vertices in canonical order.
std::vector<GrTriangle> prepareTriangles(const Scene& scene, const KernelOptions& kernel = {});

// One triangle in that layout, its vertices in the order given (not reordered).
GrTriangle prepareTriangle(const glm::vec3 v[3], int prim, const KernelOptions& kernel = {});

// The three vertices of a prepared triangle, exactly as its intersector sees them (for an
// edge layout v0 + e1 is summed in double, where it is exact).
void triangleVertices(const GrTriangle& t, glm::dvec3 v[3]);

// Throws std::logic_error when `triangles` are not in the layout `kernel` reads.
void checkTriangleLayout(const GrTriangle* triangles, size_t count, const KernelOptions& kernel);
template <typename Allocator>
void checkTriangleLayout(const std::vector<GrTriangle, Allocator>& triangles,
                         const KernelOptions& kernel) {
  checkTriangleLayout(triangles.data(), triangles.size(), kernel);
}

// World-space bounds of all triangle vertices.
Bounds sceneBounds(const Scene& scene);

}  // namespace gridrt
