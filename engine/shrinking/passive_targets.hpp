// Passive targets (thesis ch. 5.1: navigable regions are "passive occluders", seen but hiding
// nothing): prisms a region method tests against its horizon like buildings, that cast no shadow.
// The VbAoI graph (engine/vbaoi/) makes one per node, its cell extruded to the avatars' eye
// height, so that a node is in another's PVSn when some eye of the one may see some avatar eye
// of the other.
//
// How: the region's building sweep logs every shadow it queues (ShadowQueue::record_into); a
// second sweep, over the targets' own quadtree, replays that log into its queue. Each target is
// then tested against exactly the shadows whose (method-delayed) farthest point is nearer than the
// target's nearest point: the H_<d that decides a building in horizon_sweep.hpp. So a target is
// kept exactly when a building of its shape standing there would be, and the method's claim
// (conservative over its ε-disc, or not) carries over to targets unchanged; hiding nothing, the
// targets change no building's fate.
// When the eye stands at the height every target reaches (the graph's avatars' eyes), each
// target's highest slope is 0 and the order of the tests stops mattering: visible() then reads
// each bin's nearest positive shadow instead of sweeping (same answer and test counts, issue 17;
// properties/passive_targets_test.cpp holds the two paths together).
#pragma once

#include <limits>
#include <optional>
#include <vector>

#include "core/scene.hpp"
#include "engine/horizon/horizon_sweep.hpp"
#include "engine/horizon/occlusion_horizon.hpp"
#include "engine/method.hpp"
#include "engine/spatial/quadtree.hpp"

namespace cullcheck {

class PassiveTargets {
 public:
  // `targets.buildings[i].id` must be i (throws std::invalid_argument otherwise).
  PassiveTargets(Scene targets, const MethodOptions& options);

  // The ids of the targets not hidden from `region` by `shadows` (a building sweep's log), sorted.
  // Targets with known[i] set are left out (the caller holds them already). Tests are added to
  // `stats`.
  // An eye at the height every target reaches (the VbAoI graph's) takes a path without the
  // sweep's queue, with the same answer and test counts (see the .cpp).
  std::vector<ObjectId> visible(const ViewRegion& region, const std::vector<Shadow>& shadows,
                                const std::vector<char>* known, CullStatistics& stats);
  // visible() by the sweep at any eye height (what the other path is tested against).
  std::vector<ObjectId> visible_by_sweep(const ViewRegion& region, const std::vector<Shadow>& shadows,
                                         const std::vector<char>* known, CullStatistics& stats);
  std::size_t size() const { return scene_.buildings.size(); }

 private:
  void count_unknown(const std::vector<char>* known);  // fills unknown_before_
  // visible() for an eye at common_height_, without the sweep's queue (see the .cpp); nullopt
  // when an item turns out not to fit its argument.
  std::optional<std::vector<ObjectId>> visible_at_eye_height(const ViewRegion& region, const std::vector<Shadow>& shadows,
                                                             const std::vector<char>* known, CullStatistics& stats);

  Scene scene_;
  // The height every target and CVP reaches, when they all reach the same one; NaN otherwise.
  double common_height_ = std::numeric_limits<double>::quiet_NaN();
  Quadtree quadtree_;
  OcclusionHorizon horizon_;
  std::vector<std::uint32_t> unknown_before_;  // scratch of visible()
};

}  // namespace cullcheck
