#include "engine/horizon/object_space_horizon.hpp"

#include <algorithm>
#include <chrono>

#include "core/elapsed.hpp"

namespace cullcheck {

ObjectSpaceHorizonCulling::ObjectSpaceHorizonCulling(const Scene& scene, ShadowRule rule, const MethodOptions& options)
    : scene_(scene), rule_(rule), quadtree_(scene, options.quadtree_leaf_size), horizon_(options.horizon_bins) {}

std::string ObjectSpaceHorizonCulling::name() const {
  return rule_ == ShadowRule::thesis ? "oh_os_thesis" : "oh_os_conservative";
}

CullResult ObjectSpaceHorizonCulling::cull(const Camera& camera) {
  const auto start = std::chrono::steady_clock::now();
  CullResult result;
  sweep_horizon(scene_, quadtree_, horizon_, rule_, camera, result);
  std::sort(result.pvs.begin(), result.pvs.end());
  result.stats.cull_ms = ms_since(start);
  return result;
}

}  // namespace cullcheck
