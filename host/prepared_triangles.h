// Triangles in the form every intersector consumes (first vertex + two edges, GrTriangle),
// computed once per scene so all intersectors see bit-identical data.
#pragma once
#include <vector>

#include "bounds.h"
#include "gridrt_types.h"
#include "scene.h"

namespace gridrt {

std::vector<GrTriangle> prepareTriangles(const Scene& scene);

// World-space bounds of all triangle vertices.
Bounds sceneBounds(const Scene& scene);

}  // namespace gridrt
