#include "engine/frustum/view_frustum_culling.hpp"

#include "core/elapsed.hpp"
#include "engine/frustum/box_walk.hpp"

#include <algorithm>
#include <chrono>

namespace cullcheck {

ViewFrustumCulling::ViewFrustumCulling(const Scene& scene, const MethodOptions& options)
    : scene_(scene), quadtree_(scene, options.quadtree_leaf_size) {}

CullResult ViewFrustumCulling::cull(const Camera& camera) {
  const auto start = std::chrono::steady_clock::now();
  CullResult result;
  const ViewVolume volume(camera);
  const auto keep = [&volume](const Box3& box, auto...) { return volume.may_intersect(box); };
  walk_boxes(quadtree_, scene_, keep, keep, result);
  result.stats.bound_tests = result.stats.cells_tested + result.stats.buildings_tested;  // one box against the six planes each
  result.stats.cull_ms = ms_since(start);
  return result;
}

}  // namespace cullcheck
