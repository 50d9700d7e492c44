#include "engine/delta_horizon/guarded_delta_horizon.hpp"

#include <algorithm>
#include <chrono>

#include "engine/horizon/horizon_sweep.hpp"

namespace cullcheck {
namespace {

struct SkipHidden {
  const HiddenCertificate& certificate;
  bool cell(std::uint32_t c) const { return certificate.cell_hidden(c); }
  bool building(std::uint32_t b) const { return certificate.building_hidden(b); }
};

}  // namespace

GuardedDeltaHorizonCulling::GuardedDeltaHorizonCulling(const Scene& scene, const MethodOptions& options)
    : scene_(scene),
      options_(options),
      quadtree_(scene, options.quadtree_leaf_size),
      horizon_(options.horizon_bins),
      shrunk_(options.horizon_bins),
      certificate_(scene, quadtree_) {}

CullResult GuardedDeltaHorizonCulling::cull(const Camera& camera) {
  const auto start = std::chrono::steady_clock::now();
  CullResult result;
  if (!region_ || !region_->contains(camera)) {
    region_ = MotionRegion{camera, options_.delta_radius, options_.delta_height, options_.delta_turn};
    certificate_.certify(*region_, shrunk_, result.stats);
    result.stats.guard_fires = 1;
  }
  const std::uint64_t nodes = result.stats.horizon_nodes;
  result.stats.items_skipped = sweep_horizon(scene_, quadtree_, horizon_, ShadowRule::conservative, camera,
                                             SkipHidden{certificate_}, result);
  result.stats.horizon_nodes += nodes;
  std::sort(result.pvs.begin(), result.pvs.end());
  result.stats.cull_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace cullcheck
