// The viewer's camera moves, each on the camera as the command line names it (--look-at
// EYE:TARGET), so that every view the viewer shows is one `gridrt --look-at ...` renders.
// The amounts are docs/viewer.md's.
#pragma once
#include <glm/glm.hpp>

#include "bounds.h"
#include "scene.h"

namespace gridrt {

struct LookAt {
  glm::vec3 eye{0.0f}, target{0.0f, 0.0f, -1.0f};
};

// A drag with the left button turns the eye about the target by this much per pixel.
constexpr float kOrbitDegreesPerPixel = 0.25f;
// An arrow key turns it by this much.
constexpr float kOrbitDegreesPerKey = 5.0f;
// The eye's elevation above (or below) the target stays within this, so that the view
// never looks straight up or down (where --look-at's +Y up is undefined).
constexpr float kMaxElevationDegrees = 85.0f;
// A wheel notch towards the scene (or the = key) moves the eye this share of the way to the
// target; away from it (or the - key), back by the inverse factor.
constexpr float kZoomPerNotch = 0.1f;
// W, A, S, D, E, X move eye and target by this share of the scene box's diagonal.
constexpr float kFlyShareOfScene = 0.02f;

// The look-at of `camera`: its eye, and the target on its line of sight at the distance of
// the centre of `scene` (or half the box's diagonal, when the centre lies behind the eye).
// The camera's roll is not kept: --look-at's views are upright.
LookAt lookAtOf(const Camera& camera, const Bounds& scene);

// The eye turned about the vertical through the target by yaw_degrees (counter-clockwise
// seen from above, +Y up) and raised by pitch_degrees (elevation clamped to
// kMaxElevationDegrees); the distance to the target kept.
LookAt orbited(const LookAt& view, float yaw_degrees, float pitch_degrees);

// Eye and target moved together in the image plane so that points at the target's depth
// follow the pointer: dx pixels right and dy pixels down, for an image `height` pixels high
// seen through the vertical field of view yfov (radians).
LookAt panned(const LookAt& view, float dx, float dy, float yfov, int height);

// The eye moved towards the target by kZoomPerNotch of the distance per notch (notches > 0)
// or away from it (notches < 0, each the inverse of one step towards it).
LookAt zoomed(const LookAt& view, int notches);

// Eye and target moved by `step` world units along the view's right, world up (+Y) and
// forward directions, `amount` steps each (e.g. {0, 0, 1}: one step forward).
LookAt flown(const LookAt& view, const glm::vec3& amount, float step);

}  // namespace gridrt
