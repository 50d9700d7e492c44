#include "engine/horizon/object_space_horizon.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

namespace cullcheck {

double shadow_slope(ShadowRule rule, const ConvexVerticalPrism& prism, Vec3 eye, const ConvexSpan& span) {
  const Vec2 e = plan(eye);
  const double rise = prism.height - eye.z;
  if (rule == ShadowRule::thesis || rise >= 0.0) {
    const double d1 = length(prism.ring[span.first_tangent] - e);
    const double d2 = length(prism.ring[span.last_tangent] - e);
    return std::min(rise / d1, rise / d2);
  }
  return rise / min_far_chain_distance(prism.ring, e);
}

double unclipped_distance(const Camera& camera) {
  if (camera.omnidirectional()) return 0.0;
  return camera.near * std::sqrt(1.0 + std::pow(std::tan(camera.hfov / 2), 2) + std::pow(std::tan(camera.vfov / 2), 2));
}

ObjectSpaceHorizonCulling::ObjectSpaceHorizonCulling(const Scene& scene, ShadowRule rule, const MethodOptions& options)
    : scene_(scene), rule_(rule), quadtree_(scene, options.quadtree_leaf_size), horizon_(options.horizon_bins) {}

std::string ObjectSpaceHorizonCulling::name() const {
  return rule_ == ShadowRule::thesis ? "oh_os_thesis" : "oh_os_conservative";
}

double ObjectSpaceHorizonCulling::shadow_slope(const ConvexVerticalPrism& prism, Vec3 eye, const ConvexSpan& span) const {
  return cullcheck::shadow_slope(rule_, prism, eye, span);
}

CullResult ObjectSpaceHorizonCulling::cull(const Camera& camera) {
  const auto start = std::chrono::steady_clock::now();
  CullResult result;
  sweep_horizon(scene_, quadtree_, horizon_, rule_, camera, NoSkip{}, result);
  std::sort(result.pvs.begin(), result.pvs.end());
  result.stats.cull_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace cullcheck
