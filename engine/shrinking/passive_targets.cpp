#include "engine/shrinking/passive_targets.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
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
    : scene_(checked(std::move(targets))), quadtree_(scene_, options.quadtree_leaf_size), horizon_(options.horizon_bins) {
  if (!scene_.buildings.empty()) {
    const double h = scene_.buildings.front().height;
    bool uniform = std::isfinite(h);
    for (const Building& b : scene_.buildings) {
      uniform = uniform && b.height == h;
      for (const ConvexVerticalPrism& prism : b.prisms) uniform = uniform && prism.height == h;
    }
    if (uniform) common_height_ = h;
  }
}

std::vector<ObjectId> PassiveTargets::visible(const ViewRegion& region, const std::vector<Shadow>& shadows,
                                              const std::vector<char>* known, CullStatistics& stats) {
  if (region.camera.position.z == common_height_) {
    count_unknown(known);
    CullStatistics fast_stats;
    if (auto fast = visible_at_eye_height(region, shadows, known, fast_stats)) {
      add_counts(stats, fast_stats);
      return std::move(*fast);
    }
  }
  return visible_by_sweep(region, shadows, known, stats);
}

// Targets already held are left out, and so is every cell holding only such targets: a target
// casts no shadow, so nothing else depends on them (issue 17: a view cell's later samples then
// sweep only what is still unknown). unknown_before_[k]: unknown targets among the first k in
// the quadtree's order, so a cell's count is a difference.
void PassiveTargets::count_unknown(const std::vector<char>* known) {
  const auto& order = quadtree_.buildings();
  unknown_before_.resize(order.size() + 1);
  unknown_before_[0] = 0;
  for (std::size_t k = 0; k < order.size(); ++k)
    unknown_before_[k + 1] = unknown_before_[k] + (known && (*known)[order[k]] != 0 ? 0u : 1u);
}

std::vector<ObjectId> PassiveTargets::visible_by_sweep(const ViewRegion& region, const std::vector<Shadow>& shadows,
                                                       const std::vector<char>* known, CullStatistics& stats) {
  count_unknown(known);
  ShadowQueue pending;
  pending.replay(shadows);
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

// The sweep above, for an eye at the targets' common height (the VbAoI graph's case: avatars'
// eyes at the eyes' height), without its order. Every target, box and cell then reaches exactly
// the eye's height, so its highest slope is 0 (NaN at zero distance, which hides nothing), and
// the sweep hides an item popped at distance d iff every bin it reads is above 0 in H_<d: iff
// each such bin is covered by a positive shadow whose farthest point is nearer than d. That
// depends only on the nearest such shadow per bin, D(b): hidden iff max D over the bins < d.
// -D is kept in an OcclusionHorizon (a raise keeps the maximum, so raising by -farthest keeps
// the minimum farthest), with the same bin rounding as the sweep's raises and tests; the test is
// hides(span, -d), or for d = +inf (every finite shadow merged) whether every bin is covered.
// The items are tested by the sweep's own cell_hidden, box_hidden and prisms_visible, handed
// NearestShadows for the horizon. With no order left, the log is raised once unsorted and the
// targets' quadtree is walked depth first: no queue, no sort. An item whose slope comes out
// finite and nonzero (some target not at the common height after all) or whose distance is NaN
// (the sweep's order is then the queue's business) sends the call back to the sweep: nullopt.
namespace {

// hides(span, slope) as the sweep's horizon answers it for an item popped at `d`, read off the
// nearest positive shadow per bin (negated in `nearest`); `fallback` is set when the slope is
// finite and nonzero, where that reading does not apply.
struct NearestShadows {
  OcclusionHorizon& nearest;
  double d = 0.0;
  bool fallback = false;
  bool hides(const AzimuthSpan& span, double slope) {
    return read(slope, [&] { return d < HUGE_VAL ? nearest.hides(span, -d) : nearest.min_over(span) > -HUGE_VAL; });
  }
  // The same over bins box_outer_bins rounded (box_hidden's path without the span).
  bool hides_range(const BinRange& range, double slope) {
    return read(slope, [&] { return d < HUGE_VAL ? nearest.hides_range(range, -d) : nearest.min_over_range(range) > -HUGE_VAL; });
  }
  const OctantBoundaries& octant_boundaries() const { return nearest.octant_boundaries(); }

 private:
  template <class Read>
  bool read(double slope, const Read& bins) {
    if (!std::isfinite(slope)) return false;
    if (slope != 0.0) {
      fallback = true;
      return false;
    }
    return bins();
  }
};

}  // namespace

std::optional<std::vector<ObjectId>> PassiveTargets::visible_at_eye_height(const ViewRegion& region,
                                                                          const std::vector<Shadow>& shadows,
                                                                          const std::vector<char>* known,
                                                                          CullStatistics& stats) {
  horizon_.reset();
  horizon_.take_node_visits();
  for (const Shadow& s : shadows)
    if (s.slope > 0.0) s.raise(horizon_, -s.farthest);
  const ViewVolume volume(region.camera);
  const bool every_box_meets = meets_every_box(volume, quadtree_.extent(), region.radius);
  auto meets = [&](const Box3& box) { return every_box_meets || may_meet(volume, box, region.radius, region.turn); };
  const Vec3 eye = region.camera.position;
  const Vec2 e = plan(eye);
  NearestShadows test{horizon_};
  const auto& cells = quadtree_.cells();
  std::vector<ObjectId> out;
  std::vector<std::uint32_t> stack;
  std::vector<std::optional<ConvexSpan>> spans;
  if (!cells.empty() && cells[0].last > cells[0].first && unknown_before_[cells[0].last] != unknown_before_[cells[0].first])
    stack.push_back(0);
  while (!stack.empty() && !test.fallback) {
    const Quadtree::Cell& cell = cells[stack.back()];
    stack.pop_back();
    ++stats.cells_tested;
    test.d = min_distance(e, cell.bounds);
    if (std::isnan(test.d)) return std::nullopt;
    const Box3 box{{cell.bounds.lo.x, cell.bounds.lo.y, 0.0}, {cell.bounds.hi.x, cell.bounds.hi.y, cell.max_height}};
    if (!meets(box) || cell_hidden(test, cell, eye)) continue;
    quadtree_.for_each_child(
        cell,
        [&](std::uint32_t c) {
          if (unknown_before_[cells[c].last] != unknown_before_[cells[c].first]) stack.push_back(c);
        },
        [&](std::uint32_t t) {
          if (test.fallback || (known && (*known)[t] != 0)) return;
          const Building& target = scene_.buildings[t];
          ++stats.buildings_tested;
          test.d = min_distance(e, target.bounds.plan());
          if (std::isnan(test.d)) {
            test.fallback = true;
            return;
          }
          if (!meets(target.bounds) || box_hidden(test, target.bounds.plan(), target.height, eye) ||
              !prisms_visible(test, target, eye, spans))
            return;
          out.push_back(target.id);
        });
  }
  if (test.fallback) return std::nullopt;
  stats.horizon_nodes += horizon_.take_node_visits();
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace cullcheck
