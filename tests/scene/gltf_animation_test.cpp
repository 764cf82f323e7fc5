// glTF animations read, checked and posed: the test scene of animated_test_scene.h posed at
// two times against poses computed by hand (a skinned strip, a morphed quad, the camera,
// the light, a turning cube), the choice of animation, and every bad input refused with
// one line naming the animation, the sampler and the problem.
#include "gltf_animation.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "animated_scene.h"
#include "animated_test_scene.h"
#include "errors.h"
#include "gltf_document_builder.h"
#include "gltf_loader.h"

namespace gridrt {
namespace {

using test::GltfDocumentBuilder;

// What a float key, or a float cast of a double, may differ from the exact value by:
// several float ulps at magnitude 2.
constexpr float kFloatRounding = 2e-6f;

GltfDocument document(const std::string& json) {
  return GltfDocument::fromMemory(reinterpret_cast<const unsigned char*>(json.data()), json.size(),
                                  "", "anim.gltf");
}

void expectNear(const glm::vec3& got, const glm::vec3& want) {
  EXPECT_NEAR(got.x, want.x, kFloatRounding);
  EXPECT_NEAR(got.y, want.y, kFloatRounding);
  EXPECT_NEAR(got.z, want.z, kFloatRounding);
}

// The triangles of the test scene, in load order: floor 0-1, cube 2-13, morph quad 14-15,
// skinned strip 16-19.
constexpr size_t kMorphFirst = 14, kStripFirst = 16;

TEST(GltfAnimation, MorphedQuadFollowsItsCubicSplineWeights) {
  const AnimatedScene scene(document(test::makeAnimatedTestScene().animatedJson()), {}, "");
  // At t = 0.5 (u = 1/2, interval 1) the Hermite weights: w0 = 0.5 * 0.25 + 0.125 * 1.5 +
  // 0.5 * 1 - 0.125 * -0.5 = 0.875; w1 = 0.125 * 0.5 + 0.5 * 0.5 - 0.125 * 1 = 0.1875.
  // The quad's top vertices (y = 0.5) rise by w0 * 0.8 and move back by w1 * 0.6; the node
  // stands at x = 1.5.
  struct Case {
    double t, w0, w1;
  };
  for (const Case& c : {Case{0.5, 0.875, 0.1875}, Case{1.0, 1.0, 0.5}}) {
    SCOPED_TRACE(c.t);
    const Scene s = scene.at(c.t);
    const float y = float(0.5 + c.w0 * double(0.8f)), z = float(-c.w1 * double(0.6f));
    // Triangle (a, b, c) of quad a b c d: bottom-left, bottom-right, top-right.
    expectNear(s.positions[3 * kMorphFirst + 0], {1.0f, -0.5f, 0.0f});
    expectNear(s.positions[3 * kMorphFirst + 1], {2.0f, -0.5f, 0.0f});
    expectNear(s.positions[3 * kMorphFirst + 2], {2.0f, y, z});
  }
  // The still pose: the node's weights (0.25, 0).
  expectNear(scene.still().positions[3 * kMorphFirst + 2], {2.0f, float(0.5 + 0.25 * 0.8), 0.0f});
}

TEST(GltfAnimation, SkinnedStripFollowsItsAnimatedJoint) {
  const AnimatedScene scene(document(test::makeAnimatedTestScene().animatedJson()), {}, "");
  // The tip joint turns by theta about +z (slerp: theta = 60 degrees * t) at (0, 0, -1):
  // a vertex bound to it moves by R(theta) (p + (0,0,1)) - (0,0,1); the middle row is half
  // that and half the (identity) root joint. The mesh node's own translation does not
  // apply.
  for (double t : {0.5, 1.0}) {
    SCOPED_TRACE(t);
    const double theta = 60.0 * t * 3.14159265358979323846 / 180.0;
    const double c = std::cos(theta), s = std::sin(theta);
    auto tip = [&](double x, double y) { return glm::dvec3(x * c - y * s, x * s + y * c, -1.0); };
    auto middle = [&](double x) { return 0.5 * glm::dvec3(x, 0, -1) + 0.5 * tip(x, 0); };
    const Scene posed = scene.at(t);
    // Triangle 2 of the strip: the upper quad's (middle left, middle right, top right).
    const size_t first = 3 * (kStripFirst + 2);
    expectNear(posed.positions[first + 0], glm::vec3(middle(-0.3)));
    expectNear(posed.positions[first + 1], glm::vec3(middle(0.3)));
    expectNear(posed.positions[first + 2], glm::vec3(tip(0.3, 1.0)));
    // The bottom row stays on the root joint.
    expectNear(posed.positions[3 * kStripFirst], {-0.3f, -1.0f, -1.0f});
  }
}

TEST(GltfAnimation, CameraLightAndCubeFollowTheirNodes) {
  const AnimatedScene scene(document(test::makeAnimatedTestScene().animatedJson()), {}, "");
  const Scene quarter = scene.at(0.25), late = scene.at(0.75);
  ASSERT_TRUE(quarter.has_camera);
  // Camera (0,1,7) -> (0.5,1.2,6.5), light (-2,3,3) -> (2,3,3), linear over 0..1 s.
  expectNear(glm::vec3(quarter.camera.world[3]),
             {0.125f, float(1.0 + 0.25 * double(0.2f)), 6.875f});
  ASSERT_EQ(quarter.lights.size(), 1u);
  expectNear(quarter.lights[0].position, {-1.0f, 3.0f, 3.0f});
  // The cube (at x = -1.5) turns 120 degrees about +y over 0..1 s and steps to scale
  // (1.3, 0.8, 1.3) at 0.5 s. Its first vertex is the corner (-0.5, -0.5, 0.5).
  auto corner = [](double degrees, glm::dvec3 scale) {
    const double a = degrees * 3.14159265358979323846 / 180.0;
    const glm::dvec3 p = glm::dvec3(-0.5, -0.5, 0.5) * scale;
    return glm::vec3(float(-1.5 + p.x * std::cos(a) + p.z * std::sin(a)), float(p.y),
                     float(-p.x * std::sin(a) + p.z * std::cos(a)));
  };
  expectNear(quarter.positions[3 * 2], corner(30, {1, 1, 1}));
  expectNear(late.positions[3 * 2], corner(90, {double(1.3f), double(0.8f), double(1.3f)}));
  // Before the first key and after the last the channels clamp.
  expectNear(glm::vec3(scene.at(-5.0).camera.world[3]), {0.0f, 1.0f, 7.0f});
  expectNear(glm::vec3(scene.at(9.0).camera.world[3]), {0.5f, 1.2f, 6.5f});
}

TEST(GltfAnimation, PlaysOneAnimationByNameOrIndex) {
  const std::string json = test::makeAnimatedTestScene().animatedJson();
  const AnimatedScene deform(document(json), {}, "Deform");
  // "Move" does not play: the camera keeps its node's translation.
  expectNear(glm::vec3(deform.at(0.5).camera.world[3]), {0.0f, 1.0f, 7.0f});
  const AnimatedScene move(document(json), {}, "0");
  expectNear(glm::vec3(move.at(0.5).camera.world[3]),
             {0.25f, float(1.0 + 0.5 * double(0.2f)), 6.75f});
  try {
    AnimatedScene(document(json), {}, "Walk");
    ADD_FAILURE() << "no error";
  } catch (const UsageError& e) {
    EXPECT_STREQ(e.what(),
                 "anim.gltf: animation 'Walk' not found; available: 0 = 'Move', 1 = 'Deform'");
  }
}

TEST(GltfAnimation, TheLaterAnimationWinsOnTheSameProperty) {
  auto translating = [](double x) {
    Animation a;
    AnimationChannel c;
    c.node = 0;
    c.track.width = 3;
    c.track.times = {0};
    c.track.values = {x, 0, 0};
    a.channels.push_back(c);
    return a;
  };
  const std::vector<Animation> animations{translating(1), translating(2)};
  EXPECT_EQ(poseAt(animations, {0, 1}, 1, 0.0)[0].translation, glm::dvec3(2, 0, 0));
  EXPECT_EQ(poseAt(animations, {1, 0}, 1, 0.0)[0].translation, glm::dvec3(1, 0, 0));
}

// ---------------------------------------------------------------------------------------------
// Bad input

// One triangle on node 0 (with two morph targets where `morph`), node 1 empty, and one
// animation "Bad" of the given samplers and channels.
std::string badDocument(GltfDocumentBuilder& b, const std::string& samplers,
                        const std::string& channels, const std::string& node1 = "{}") {
  const int pos = b.floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3");
  return b.json("\"scenes\":[{\"nodes\":[0,1]}],\"nodes\":[{\"mesh\":0}," + node1 +
                "],\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":" +
                std::to_string(pos) + "}}]}],\"animations\":[{\"name\":\"Bad\",\"samplers\":[" +
                samplers + "],\"channels\":[" + channels + "]}]");
}

std::string sampler(int input, int output, const std::string& interpolation = "LINEAR") {
  return "{\"input\":" + std::to_string(input) + ",\"output\":" + std::to_string(output) +
         ",\"interpolation\":\"" + interpolation + "\"}";
}

std::string channel(int sampler_index, int node, const std::string& path) {
  return "{\"sampler\":" + std::to_string(sampler_index) +
         ",\"target\":{\"node\":" + std::to_string(node) + ",\"path\":\"" + path + "\"}}";
}

// The message reading the animations of `json` throws.
std::string animationError(const std::string& json) {
  try {
    std::vector<std::string> warnings;
    readAnimations(document(json).model(), "anim.gltf", warnings);
  } catch (const SceneError& e) {
    const std::string message = e.what();
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    return message;
  }
  return "<no error>";
}

TEST(GltfAnimation, RefusesOutputCountsThatDisagreeWithTheInput) {
  GltfDocumentBuilder b;
  const int times = b.floats({0, 1, 2}, "SCALAR");
  const int two = b.floats({0, 0, 0, 1, 1, 1}, "VEC3");
  EXPECT_EQ(animationError(badDocument(b, sampler(times, two), channel(0, 1, "translation"))),
            "anim.gltf: animation 0 'Bad' sampler 0 (channel 0): input has 3 key times but "
            "output has 2 elements (translation needs 3)");
  GltfDocumentBuilder c;
  const int times2 = c.floats({0, 1}, "SCALAR");
  const int values2 = c.floats({0, 0, 0, 1, 1, 1}, "VEC3");
  EXPECT_EQ(animationError(
                badDocument(c, sampler(times2, values2, "CUBICSPLINE"), channel(0, 1, "scale"))),
            "anim.gltf: animation 0 'Bad' sampler 0 (channel 0): input has 2 key times but "
            "output has 2 elements (CUBICSPLINE scale needs 6)");
}

TEST(GltfAnimation, RefusesTimesThatDoNotIncrease) {
  for (const std::vector<float>& keys : {std::vector<float>{0, 1, 1}, {0, 2, 1}}) {
    GltfDocumentBuilder b;
    const int times = b.floats(keys, "SCALAR");
    const int values = b.floats({0, 0, 0, 1, 1, 1, 2, 2, 2}, "VEC3");
    const std::string message =
        animationError(badDocument(b, sampler(times, values), channel(0, 1, "translation")));
    EXPECT_EQ(message.rfind("anim.gltf: animation 0 'Bad' sampler 0 (channel 0): input times "
                            "do not increase: time 2 (",
                            0),
              0u)
        << message;
  }
}

TEST(GltfAnimation, RefusesNanKeys) {
  const float nan = std::nanf("");
  GltfDocumentBuilder b;
  const int times = b.floats({0, nan}, "SCALAR");
  const int values = b.floats({0, 0, 0, 1, 1, 1}, "VEC3");
  EXPECT_EQ(animationError(badDocument(b, sampler(times, values), channel(0, 1, "translation"))),
            "anim.gltf: animation 0 'Bad' sampler 0 (channel 0): input time 1 is NaN");
  GltfDocumentBuilder c;
  const int good_times = c.floats({0, 1}, "SCALAR");
  const int nan_values = c.floats({0, 0, 0, nan, 1, 1}, "VEC3");
  EXPECT_EQ(
      animationError(badDocument(c, sampler(good_times, nan_values), channel(0, 1, "translation"))),
      "anim.gltf: animation 0 'Bad' sampler 0 (channel 0): output value 3 is NaN");
}

TEST(GltfAnimation, RefusesChannelsAimedAtMissingOrUnanimatableNodes) {
  auto error = [](const std::string& path, int node, const std::string& node1) {
    GltfDocumentBuilder b;
    const int times = b.floats({0, 1}, "SCALAR");
    const int values = b.floats({0, 0, 0, 1, 1, 1}, "VEC3");
    return animationError(badDocument(b, sampler(times, values), channel(0, node, path), node1));
  };
  EXPECT_EQ(error("translation", 5, "{}"),
            "anim.gltf: animation 0 'Bad' sampler 0 (channel 0): target node 5 does not exist "
            "(2 nodes)");
  EXPECT_EQ(error("translation", 1, "{\"matrix\":[1,0,0,0,0,1,0,0,0,0,1,0,0,0,0,1]}"),
            "anim.gltf: animation 0 'Bad' sampler 0 (channel 0): targets node 1 translation of "
            "a node with a matrix (glTF allows only TRS on animated nodes)");
  EXPECT_EQ(error("weights", 0, "{}"),
            "anim.gltf: animation 0 'Bad' sampler 0 (channel 0): weights of a node without "
            "morph targets");
}

TEST(GltfAnimation, RefusesOtherMalformedSamplersAndChannels) {
  // Accessors 0 (times), 1 (values) and 2 (the triangle).
  auto error = [](const std::string& interpolation, int output, const std::string& channels) {
    GltfDocumentBuilder b;
    const int times = b.floats({0, 1}, "SCALAR");
    const int values = b.floats({0, 0, 0, 1, 1, 1}, "VEC3");
    return animationError(
        badDocument(b, sampler(times, output < 0 ? values : output, interpolation), channels));
  };
  EXPECT_EQ(error("LINEAR", -1, channel(3, 1, "translation")),
            "anim.gltf: animation 0 'Bad' channel 0: sampler 3 does not exist (1 samplers)");
  EXPECT_EQ(error("BEZIER", -1, channel(0, 1, "translation")),
            "anim.gltf: animation 0 'Bad' sampler 0 (channel 0): interpolation 'BEZIER' is not "
            "LINEAR, STEP or CUBICSPLINE");
  EXPECT_EQ(error("LINEAR", -1, channel(0, 1, "rotation")),
            "anim.gltf: animation 0 'Bad' sampler 0 (channel 0): rotation output must be FLOAT "
            "or normalized VEC4, not FLOAT VEC3");
  EXPECT_EQ(error("LINEAR", -1, channel(0, 1, "translation") + "," + channel(0, 1, "translation")),
            "anim.gltf: animation 0 'Bad' sampler 0 (channel 1): node 1 translation is animated "
            "twice by this animation");
  EXPECT_EQ(error("LINEAR", 99, channel(0, 1, "translation")),
            "anim.gltf: animation 0 'Bad' sampler 0 (channel 0): output accessor 99 does not "
            "exist (3 accessors)");
}

TEST(GltfAnimation, RefusesAZeroRotationKey) {
  // Slerp would normalise it into NaN, and the node's triangles would vanish in silence.
  GltfDocumentBuilder b;
  const int times = b.floats({0, 1}, "SCALAR");
  const int keys = b.floats({0, 0, 0, 1, 0, 0, 0, 0}, "VEC4");
  EXPECT_EQ(animationError(badDocument(b, sampler(times, keys), channel(0, 0, "rotation"))),
            "anim.gltf: animation 0 'Bad' sampler 0 (channel 0): rotation key 1 is a zero "
            "quaternion");
}

TEST(GltfAnimation, WarnsAboutChannelsItCannotPlay) {
  GltfDocumentBuilder b;
  const int times = b.floats({0, 1}, "SCALAR");
  const int values = b.floats({0, 0, 0, 1, 1, 1}, "VEC3");
  const std::string json = badDocument(b, sampler(times, values), channel(0, 1, "pointer"));
  std::vector<std::string> warnings;
  const std::vector<Animation> animations =
      readAnimations(document(json).model(), "anim.gltf", warnings);
  ASSERT_EQ(animations.size(), 1u);
  EXPECT_TRUE(animations[0].channels.empty());
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_EQ(warnings[0],
            "animation 0 'Bad' sampler 0 (channel 0): target path 'pointer' is not supported; "
            "ignored");
}

}  // namespace
}  // namespace gridrt
