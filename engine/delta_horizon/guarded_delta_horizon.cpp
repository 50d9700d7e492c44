#include "engine/delta_horizon/guarded_delta_horizon.hpp"

#include <algorithm>
#include <chrono>

#include "engine/horizon/horizon_sweep.hpp"

namespace cullcheck {
namespace {

// Swept buildings front to back from `from`. (distance, index) pairs are totally ordered, so the
// order does not depend on the order the sort starts from (the last frame's, or the prefetched
// region's centre's: nearly sorted either way).
void sort_by_distance(std::vector<std::pair<double, std::uint32_t>>& order, const Scene& scene, Vec2 from) {
  for (auto& [distance, b] : order) distance = min_distance(from, scene.buildings[b].bounds.plan());
  std::sort(order.begin(), order.end());
}

}  // namespace

GuardedDeltaHorizonCulling::GuardedDeltaHorizonCulling(const Scene& scene, const MethodOptions& options)
    : scene_(scene),
      options_(options),
      quadtree_(scene, options.quadtree_leaf_size),
      horizon_(options.horizon_bins),
      final_(options.horizon_bins),
      first_(scene, quadtree_, options.horizon_bins),
      second_(scene, quadtree_, options.horizon_bins) {}

GuardedDeltaHorizonCulling::~GuardedDeltaHorizonCulling() = default;

CullResult GuardedDeltaHorizonCulling::cull(const Camera& camera) {
  const auto start = std::chrono::steady_clock::now();
  CullResult result;
  CullStatistics& stats = result.stats;
  if (!region_ || !region_->contains(camera)) {
    // The region is centred ahead of the eye, along its last plan step (0.9 ε ahead, so this
    // camera is inside): walking on, the eye crosses the whole disc before the guard fires again.
    Camera anchor = camera;
    Vec2 direction{0.0, 0.0};
    if (last_camera_) {
      const Vec2 step = plan(camera.position) - plan(last_camera_->position);
      const double l = length(step);
      if (l > 0.0 && l < options_.delta_radius) {
        direction = step * (1.0 / l);
        const Vec2 ahead = direction * (0.9 * options_.delta_radius);
        anchor.position = {camera.position.x + ahead.x, camera.position.y + ahead.y, camera.position.z};
      }
    }
    bool prefetched = false;
    if (prefetch_.pending()) {
      prefetch_.wait();  // rethrows what the thread threw
      if (next_region_->contains(camera)) {
        std::swap(current_, spare_);
        region_ = *next_region_;
        stats = next_stats_;
        order_.swap(next_order_);  // sorted from the region's centre: nearly sorted from here
        prefetched = true;
        ++prefetch_hits_;
      }
    }
    if (!prefetched) {
      region_ = MotionRegion{anchor, options_.delta_radius, options_.delta_height, options_.delta_turn};
      current_->certify(*region_, stats);
      order_.clear();
      for (std::uint32_t b : current_->swept()) order_.push_back({0.0, b});
    }
    stats.guard_fires = 1;
    // Next: where re-anchoring on a straight walk would put the region, 1.9 ε on from this one's
    // centre (the eye leaves this disc about ε ahead of the centre and anchors 0.9 ε beyond).
    if (options_.delta_prefetch && (direction.x != 0.0 || direction.y != 0.0)) {
      Camera next = camera;
      const Vec2 on = plan(region_->anchor.position) + direction * (1.9 * options_.delta_radius);
      next.position = {on.x, on.y, camera.position.z};
      next_region_ = MotionRegion{next, options_.delta_radius, options_.delta_height, options_.delta_turn};
      next_stats_ = CullStatistics{};
      prefetch_.start([this] {
        spare_->certify(*next_region_, next_stats_);
        next_order_.clear();
        for (std::uint32_t b : spare_->swept()) next_order_.push_back({0.0, b});
        sort_by_distance(next_order_, scene_, plan(next_region_->anchor.position));
      });
    }
  }
  const ViewVolume volume(camera);
  const Vec3 eye = camera.position;
  const Vec2 e = plan(eye);
  const double unclipped = unclipped_distance(camera);

  sort_by_distance(order_, scene_, e);

  horizon_.reset();
  horizon_.restrict_to(azimuth_coverage(camera));
  horizon_.take_node_visits();
  ShadowQueue pending;
  std::vector<std::optional<ConvexSpan>> spans;
  std::vector<std::uint32_t> found;  // uncertain buildings found visible
  for (const auto& [distance, b] : order_) {
    pending.merge_nearer_than(distance, horizon_, stats);
    const Building& building = scene_.buildings[b];
    if (current_->certainly_visible(b)) {
      spans.clear();
      for (const ConvexVerticalPrism& prism : building.prisms) spans.push_back(convex_span(prism.ring, e));
    } else {
      ++stats.buildings_tested;
      if (!volume.may_intersect(building.bounds) || box_hidden(horizon_, building.bounds.plan(), building.height, eye) ||
          !prisms_visible(horizon_, building, eye, spans))
        continue;
      found.push_back(b);
    }
    queue_shadows(pending, ShadowRule::conservative, building, eye, distance, unclipped, spans);
  }
  stats.horizon_nodes += horizon_.take_node_visits();
  stats.items_skipped = current_->visible().size() + current_->hidden_count();

  last_pvs_ = current_->visible();
  last_pvs_.insert(last_pvs_.end(), found.begin(), found.end());
  result.pvs.reserve(last_pvs_.size());
  for (std::uint32_t b : last_pvs_) result.pvs.push_back(scene_.buildings[b].id);
  std::sort(result.pvs.begin(), result.pvs.end());
  last_camera_ = camera;
  stats.cull_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return result;
}

OcclusionHorizon& GuardedDeltaHorizonCulling::horizon() {
  final_.reset();
  if (!last_camera_) return final_;
  const Camera& camera = *last_camera_;
  final_.restrict_to(azimuth_coverage(camera));
  const Vec3 eye = camera.position;
  const Vec2 e = plan(eye);
  const double unclipped = unclipped_distance(camera);
  ShadowQueue shadows;
  CullStatistics unused;
  std::vector<std::optional<ConvexSpan>> spans;
  for (std::uint32_t b : last_pvs_) {
    const Building& building = scene_.buildings[b];
    spans.clear();
    for (const ConvexVerticalPrism& prism : building.prisms) spans.push_back(convex_span(prism.ring, e));
    queue_shadows(shadows, ShadowRule::conservative, building, eye, min_distance(e, building.bounds.plan()), unclipped, spans);
  }
  shadows.merge_all(final_, unused);
  return final_;
}

}  // namespace cullcheck
