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
  for (const Shadow& s : shadows) pending.push(s.farthest, s.span, s.slope);
  CullResult result;
  sweep_horizon(
      scene_, quadtree_, horizon_, region.camera, /*restrict_to_coverage=*/false,
      [&](const ViewVolume& volume, const Box3& box) { return may_meet(volume, box, region.radius, region.turn); },
      [](ShadowQueue&, std::uint32_t, Vec3, double, double, const std::vector<std::optional<ConvexSpan>>&) {},
      [&](std::uint32_t t) { return known && (*known)[t] != 0; }, pending, result);
  stats.cells_tested += result.stats.cells_tested;
  stats.buildings_tested += result.stats.buildings_tested;
  stats.horizon_nodes += result.stats.horizon_nodes;
  stats.items_skipped += result.stats.items_skipped;
  std::sort(result.pvs.begin(), result.pvs.end());
  return result.pvs;
}

}  // namespace cullcheck
