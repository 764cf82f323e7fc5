// -v / --verbose: what the program chose for this render (scene, camera, lights, grid,
// intersector and passes), one line each, printed on stderr before it renders.
#pragma once
#include <string>
#include <vector>

#include "options.h"
#include "scene.h"
#include "uniform_grid.h"

namespace gridrt {

// `grid` is null when the intersector uses none (brute, reference).
std::vector<std::string> choicesReport(const Options& o, const Scene& scene, const Camera& camera,
                                       const UniformGrid* grid, double build_ms);

}  // namespace gridrt
