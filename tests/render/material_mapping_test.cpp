// The glTF metallic-roughness material mapped onto Whitted/Phong terms (whitted_shading.h):
// at the corners of the metallic x roughness square and for the glTF default material no
// surface with a non-black base colour loses all its light, and none reflects more than
// its base colour between the Lambert lobe and the mirror.
#include <gtest/gtest.h>

#include "whitted_shading.h"

namespace gridrt {
namespace {

const glm::vec3 kBase(0.5f, 0.6f, 0.7f);

Material metalRough(float metallic, float roughness, glm::vec3 base = kBase) {
  Material m;
  m.base_color = base;
  m.metallic = metallic;
  m.roughness = roughness;
  return m;
}

TEST(MaterialMapping, EveryCornerOfTheMetallicRoughnessSquareReflectsItsColour) {
  for (float metallic : {0.0f, 1.0f})
    for (float roughness : {0.0f, 1.0f}) {
      const SurfaceTerms s = surfaceTerms(metalRough(metallic, roughness));
      const glm::vec3 reflected = s.diffuse + s.mirror;
      SCOPED_TRACE(testing::Message() << "metallic " << metallic << " roughness " << roughness);
      for (int c = 0; c < 3; ++c) {
        // A dielectric keeps its base as albedo; a metal splits it between mirror and lobe.
        EXPECT_FLOAT_EQ(reflected[c], kBase[c]);
      }
    }
}

TEST(MaterialMapping, RoughMetalScattersItsColourDiffusely) {
  const SurfaceTerms s = surfaceTerms(metalRough(1.0f, 1.0f));
  EXPECT_EQ(s.diffuse, kBase);
  EXPECT_EQ(s.mirror, glm::vec3(0.0f));
  const SurfaceTerms half = surfaceTerms(metalRough(1.0f, 0.5f));
  EXPECT_EQ(half.mirror, kBase * 0.25f);  // the smooth share (1 - 0.5)^2
  EXPECT_EQ(half.diffuse, kBase * 0.75f);
}

// glTF's default material (a material without pbrMetallicRoughness): white, metallic 1,
// roughness 1. It must not render black.
TEST(MaterialMapping, TheGltfDefaultMaterialIsNotBlack) {
  const SurfaceTerms s = surfaceTerms(metalRough(1.0f, 1.0f, glm::vec3(1.0f)));
  EXPECT_EQ(s.diffuse, glm::vec3(1.0f));
}

TEST(MaterialMapping, ABlackBaseStaysBlack) {
  for (float metallic : {0.0f, 0.5f, 1.0f}) {
    const SurfaceTerms s = surfaceTerms(metalRough(metallic, 0.7f, glm::vec3(0.0f)));
    EXPECT_EQ(s.diffuse + s.mirror, glm::vec3(0.0f));
  }
}

}  // namespace
}  // namespace gridrt
