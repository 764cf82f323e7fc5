// A test on the built-in default scene with an OpenCL device (skipped without one): the
// runtime, the scene and its prepared triangles, made fresh for each test; random points
// inside the scene's box.
#pragma once
#include <gtest/gtest.h>

#include <glm/glm.hpp>
#include <memory>
#include <random>
#include <vector>

#include "bounds.h"
#include "cl_runtime.h"
#include "default_scene.h"
#include "prepared_triangles.h"

namespace gridrt::test {

class DefaultSceneTest : public ::testing::Test {
 protected:
  void SetUp() override {
    if (listDevices().empty()) GTEST_SKIP() << "no OpenCL device: install pocl-opencl-icd";
    runtime_ = std::make_unique<ClRuntime>("");
    scene_ = makeDefaultScene();
    triangles_ = prepareTriangles(scene_);
  }
  // A point inside the scene's box (shrunk by a tenth on each side).
  glm::vec3 inside(std::mt19937& rng) const {
    std::uniform_real_distribution<float> u(0.1f, 0.9f);
    const Bounds b = sceneBounds(scene_);
    return b.lo + glm::vec3(u(rng), u(rng), u(rng)) * (b.hi - b.lo);
  }
  std::unique_ptr<ClRuntime> runtime_;
  Scene scene_;
  std::vector<GrTriangle> triangles_;
};

}  // namespace gridrt::test
