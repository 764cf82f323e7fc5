// A test on the built-in default scene with an OpenCL device (skipped without one): the
// runtime, the scene and its prepared triangles, made fresh for each test.
#pragma once
#include <gtest/gtest.h>

#include <memory>
#include <vector>

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
  std::unique_ptr<ClRuntime> runtime_;
  Scene scene_;
  std::vector<GrTriangle> triangles_;
};

}  // namespace gridrt::test
