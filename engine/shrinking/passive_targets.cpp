#include "engine/shrinking/passive_targets.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "engine/delta_horizon/motion_region.hpp"

namespace cullcheck {
namespace {

Scene checked(Scene targets) {
  for (std::size_t i = 0; i < targets.buildings.size(); ++i)
    if (targets.buildings[i].id != i)
      throw std::invalid_argument("passive targets: target " + std::to_string(i) + " has id " +
                                  std::to_string(targets.buildings[i].id) + "; ids must be the targets' indices");
  return targets;
}

}  // namespace

PassiveTargets::PassiveTargets(Scene targets, const MethodOptions& options)
    : scene_(checked(std::move(targets))), quadtree_(scene_, options.quadtree_leaf_size), horizon_(options.horizon_bins) {}

std::vector<ObjectId> PassiveTargets::visible(const ViewRegion& region, const std::vector<Shadow>& shadows,
                                              const std::vector<char>* known, CullStatistics& stats) {
  ShadowQueue pending;
  pending.replay(shadows);
  // Targets already held are left out, and so is every cell holding only such targets: a target
  // casts no shadow, so nothing else depends on them (issue 17: a view cell's later samples then
  // sweep only what is still unknown). unknown_before_[k]: unknown targets among the first k in
  // the quadtree's order, so a cell's count is a difference.
  const auto& order = quadtree_.buildings();
  unknown_before_.resize(order.size() + 1);
  unknown_before_[0] = 0;
  for (std::size_t k = 0; k < order.size(); ++k)
    unknown_before_[k + 1] = unknown_before_[k] + (known && (*known)[order[k]] != 0 ? 0u : 1u);
  const auto& cells = quadtree_.cells();
  CullResult result;
  sweep_horizon(
      scene_, quadtree_, horizon_, region.camera, /*restrict_to_coverage=*/false,
      [&](const ViewVolume& volume, const Box3& box) { return may_meet(volume, box, region.radius, region.turn); },
      [](ShadowQueue&, std::uint32_t, Vec3, double, double, const std::vector<std::optional<ConvexSpan>>&) {},
      [](std::uint32_t) { return false; },
      [&](bool is_target, std::uint32_t i) {
        if (is_target) return known && (*known)[i] != 0;
        return unknown_before_[cells[i].last] == unknown_before_[cells[i].first];
      },
      pending, result, /*cast_reads_spans=*/false, /*target_margin=*/0.0, /*finish_horizon=*/false);
  result.stats.occluders_applied = 0;  // the replayed shadows: the building sweep counted them
  add_counts(stats, result.stats);
  std::sort(result.pvs.begin(), result.pvs.end());
  return result.pvs;
}

}  // namespace cullcheck
