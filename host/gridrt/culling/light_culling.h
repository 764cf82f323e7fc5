// Packet culling for shadow rays towards a point or spot light. Those rays share no origin
// but end at the light (up to their offset and rounding), so seen from the light they form
// a pinhole image, as camera rays do from the eye: the light bundles (light_bundles.h) sort
// them by the cube face their direction (from the light) meets, and for each face the PE
// kernel culls a packet's triangles with the camera's test (packet_culling.h) in a frame
// looking out of that face, a lane's (a, b) the same for d and -d. The triangles' boxes
// are seen from the light and grown by what the rays' own origins add (TowardsOrigin), so
// no triangle a lane's test could hit is skipped and the hits stay those of brute force.
#pragma once
#include <array>
#include <glm/glm.hpp>
#include <vector>

#include "gridrt_types.h"
#include "packet_culling.h"

namespace gridrt {

// The culling frame of cube face `face` (2 * axis + 1 for the negative side, as in
// light_bundles.cpp): forward the face's outward axis, right and up the two other axes.
GrCullFrame cubeFaceFrame(int face);

// The six faces' frames and box planes for one light, kept while the light and the
// triangles stay and the batches' bounds stay within those the boxes were made for.
class LightCullCache {
 public:
  // Makes the boxes of the `faces` that hold rays, for rays within `bounds` towards
  // `light` (their bounds as measured by the light bundles); false when nothing changed
  // (the device copy is current). Culling is off for a batch whose rays end nowhere near
  // the light (usable).
  bool update(const glm::vec3& light, const TowardsOrigin& bounds, const std::array<bool, 6>& faces,
              const GrTriangle* triangles, size_t count);
  static bool usable(const TowardsOrigin& bounds);
  const std::array<GrCullFrame, 6>& frames() const { return frames_; }
  // Face f's four planes from f * 4 * stride() on.
  const std::vector<float>& planes() const { return planes_; }
  size_t stride() const { return stride_; }

 private:
  glm::vec3 light_{0.0f};
  TowardsOrigin made_for_;      // the bounds the boxes were grown for
  std::array<bool, 6> made_{};  // faces with boxes
  size_t count_ = 0, stride_ = 0;
  std::array<GrCullFrame, 6> frames_{};
  std::vector<float> planes_;
};

}  // namespace gridrt
