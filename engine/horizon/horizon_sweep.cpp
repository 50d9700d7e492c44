#include "engine/horizon/horizon_sweep.hpp"

#include <algorithm>
#include <cmath>

namespace cullcheck {

double shadow_slope(ShadowRule rule, const ConvexVerticalPrism& prism, Vec3 eye, const ConvexSpan& span) {
  const Vec2 e = plan(eye);
  const double rise = prism.height - eye.z;
  if (rule == ShadowRule::thesis || rise >= 0.0) {
    // length(ring[tangent] - e), as convex_span measured it.
    return std::min(rise / span.first_distance, rise / span.last_distance);
  }
  return rise / min_far_chain_distance(prism.ring, e);
}

double unclipped_distance(const Camera& camera) {
  if (camera.omnidirectional()) return 0.0;
  return camera.near * std::sqrt(1.0 + std::pow(std::tan(camera.hfov / 2), 2) + std::pow(std::tan(camera.vfov / 2), 2));
}

}  // namespace cullcheck
