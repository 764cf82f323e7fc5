#include "light_culling.h"

#include <algorithm>
#include <cmath>

#include "prefault.h"

namespace gridrt {

GrCullFrame cubeFaceFrame(int face) {
  const int a = face / 2, b = (a + 1) % 3, c = (a + 2) % 3;
  const float s = face % 2 ? -1.0f : 1.0f;
  float f[3] = {0, 0, 0}, r[3] = {0, 0, 0}, u[3] = {0, 0, 0};
  f[a] = s;
  r[b] = 1.0f;
  u[c] = 1.0f;
  GrCullFrame frame{};
  frame.fx = f[0], frame.fy = f[1], frame.fz = f[2], frame.enabled = 1.0f;
  frame.rx = r[0], frame.ry = r[1], frame.rz = r[2];
  frame.ux = u[0], frame.uy = u[1], frame.uz = u[2];
  return frame;
}

bool LightCullCache::usable(const TowardsOrigin& bounds) {
  return std::isfinite(bounds.miss) && std::isfinite(bounds.ray_reach) && bounds.min_length > 0.0;
}

bool LightCullCache::update(const glm::vec3& light, const TowardsOrigin& bounds,
                            const std::array<bool, 6>& faces, const GrTriangle* triangles,
                            size_t count) {
  // Boxes grown for larger bounds serve smaller ones; when a batch outgrows them they are
  // made again with twice its bounds, so that frames of a still light make them once.
  const bool stale = light != light_ || count != count_ || bounds.miss > made_for_.miss ||
                     bounds.ray_reach > made_for_.ray_reach ||
                     bounds.min_length < made_for_.min_length;
  if (stale) {
    made_.fill(false);
    light_ = light;
    count_ = count;
    made_for_ = bounds;
    made_for_.miss = 2.0 * bounds.miss;
    made_for_.ray_reach = 2.0 * bounds.ray_reach;
    made_for_.min_length = 0.5 * bounds.min_length;
    stride_ = count + kCullPlanePadding;
    if (planes_.size() != 6 * 4 * stride_) {
      reserveFaultedIn(planes_, 6 * 4 * stride_);  // fresh memory: on every core (prefault.h)
      planes_.assign(6 * 4 * stride_, 0.0f);
    }
  }
  bool changed = false;
  for (int f = 0; f < 6; ++f) {
    if (!faces[f] || made_[f]) continue;
    frames_[f] = cubeFaceFrame(f);
    writeTowardsOriginBoxPlanes(frames_[f], light, made_for_, triangles, count,
                                planes_.data() + size_t(f) * 4 * stride_, stride_);
    made_[f] = changed = true;
  }
  return changed;
}

}  // namespace gridrt
