// Triangles in the form every intersector consumes (first vertex + two edges, GrTriangle),
// computed once per scene so all intersectors see bit-identical data.
#pragma once
#include <vector>

#include "bounds.h"
#include "gridrt_types.h"
#include "intersector.h"
#include "scene.h"

namespace gridrt {

// In the layout the kernels of `kernel` read: edges for Moeller-Trumbore, vertices for
// the watertight test.
std::vector<GrTriangle> prepareTriangles(const Scene& scene, const KernelOptions& kernel = {});

// The three vertices of a prepared triangle, exactly as its intersector sees them (for an
// edge layout v0 + e1 is summed in double, where it is exact).
void triangleVertices(const GrTriangle& t, glm::dvec3 v[3]);

// Throws std::logic_error when `triangles` are not in the layout `kernel` reads.
void checkTriangleLayout(const std::vector<GrTriangle>& triangles, const KernelOptions& kernel);

// World-space bounds of all triangle vertices.
Bounds sceneBounds(const Scene& scene);

}  // namespace gridrt
