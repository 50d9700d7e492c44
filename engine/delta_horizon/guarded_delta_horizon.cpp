#include "engine/delta_horizon/guarded_delta_horizon.hpp"

#include <algorithm>
#include <array>
#include <chrono>

#include "core/elapsed.hpp"
#include "engine/horizon/horizon_sweep.hpp"

namespace cullcheck {
namespace {

// Swept buildings front to back from `from`. (distance, index) pairs are totally ordered, so the
// order does not depend on the order the sort starts from (the last frame's, the certificate's
// sweep from the anchor, or the prefetched region's centre's: nearly sorted each time). So an
// insertion sort, which costs little more than a pass over a nearly sorted list; one that has
// moved entries by more than 8 places each on average is finished by std::sort instead.
template <class Swept>
void sort_by_distance(std::vector<Swept>& order, const Scene& scene, Vec2 from) {
  for (Swept& s : order) s.distance = min_distance(from, scene.buildings[s.building].bounds.plan());
  std::size_t moves = 0;
  const std::size_t budget = 8 * order.size();
  for (std::size_t i = 1; i < order.size(); ++i) {
    const Swept s = order[i];
    std::size_t j = i;
    for (; j > 0 && s < order[j - 1]; --j) order[j] = order[j - 1];
    order[j] = s;
    moves += i - j;
    if (moves > budget) {
      std::sort(order.begin(), order.end());
      return;
    }
  }
}

// The certificate's swept buildings, each with the vertices fixed over the region's disc (its
// box's corners, then each CVP's ring). The disc is widened by 1e-9 of its radius so that an eye
// MotionRegion::contains admits within rounding is inside it. With the certainly visible
// buildings' ids, sorted: the part of every query's PVS known in advance.
template <class Swept>
void fix_vertices(const RegionCertificate& certificate, const MotionRegion& region, const Scene& scene,
                  std::vector<Swept>& order, std::vector<DiscVertices>& vertices, std::vector<ObjectId>& visible_ids) {
  visible_ids.clear();
  for (std::uint32_t b : certificate.visible()) visible_ids.push_back(scene.buildings[b].id);
  std::sort(visible_ids.begin(), visible_ids.end());
  order.clear();
  vertices.clear();
  const Vec2 centre = plan(region.anchor.position);
  const double radius = region.radius * (1.0 + 1e-9);
  for (std::uint32_t b : certificate.swept()) {
    const Building& building = scene.buildings[b];
    order.push_back({0.0, b, static_cast<std::uint32_t>(vertices.size())});
    for (const ConvexVerticalPrism& prism : building.prisms)
      vertices.push_back(disc_vertices(prism.ring.data(), prism.ring.size(), centre, radius));
  }
}

// queue_shadows for a certainly visible building: the same shadows in the same order, but where
// a CVP's tangents are fixed for the region, its shadow carries the bins raise() would take of
// span_from_tangents' span, found without the span (span_inner_bins: no atan2). Elsewhere, and
// where those bins are not certain, the span is computed as before.
template <class FarthestOf>
void queue_fixed_shadows(ShadowQueue& pending, const Building& building, const DiscVertices* fixed, Vec3 eye,
                         double distance, double unclipped, const OctantBoundaries& boundaries,
                         const FarthestOf& farthest_of) {
  const Vec2 e = plan(eye);
  const bool may_be_clipped = distance < unclipped;
  for (std::size_t p = 0; p < building.prisms.size(); ++p) {
    const ConvexVerticalPrism& prism = building.prisms[p];
    const std::vector<Vec2>& ring = prism.ring;
    const DiscVertices& v = fixed[p];
    if (v.tangents_fixed()) {
      const Vec2 lo = ring[v.first_tangent], hi = ring[v.last_tangent];
      const Vec2 dlo = lo - e, dhi = hi - e;
      const double llo = length(dlo), lhi = length(dhi);
      if (const auto bins = span_inner_bins(dlo, dhi, tangent_slack(lo, hi, e, llo, lhi), boundaries)) {
        const ConvexSpan tangents{{}, v.first_tangent, v.last_tangent, llo, lhi};  // what shadow_slope reads
        queue_prism_shadow(pending, ShadowRule::conservative, prism, p, eye, may_be_clipped, unclipped, tangents, *bins,
                           farthest_of);
        continue;
      }
    }
    if (const auto span = span_from_tangents(ring.data(), ring.size(), v, e))
      queue_prism_shadow(pending, ShadowRule::conservative, prism, p, eye, may_be_clipped, unclipped, *span, span->span,
                         farthest_of);
  }
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
      stats.background_ms = next_stats_.background_ms;  // spent whether it is taken or not
      if (next_region_->contains(camera)) {
        std::swap(current_, spare_);
        region_ = *next_region_;
        stats = next_stats_;
        order_.swap(next_order_);  // sorted from the region's centre: nearly sorted from here
        vertices_.swap(next_vertices_);
        visible_ids_.swap(next_visible_ids_);
        prefetched = true;
        ++prefetch_hits_;
      }
    }
    if (!prefetched) {
      region_ = MotionRegion{anchor, options_.delta_radius, options_.delta_height, options_.delta_turn};
      current_->certify(*region_, stats);
      fix_vertices(*current_, *region_, scene_, order_, vertices_, visible_ids_);
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
        const auto began = std::chrono::steady_clock::now();
        spare_->certify(*next_region_, next_stats_);
        fix_vertices(*spare_, *next_region_, scene_, next_order_, next_vertices_, next_visible_ids_);
        sort_by_distance(next_order_, scene_, plan(next_region_->anchor.position));
        next_stats_.background_ms = ms_since(began);
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
  ShadowQueue& pending = pending_;
  pending.clear();
  std::vector<std::optional<ConvexSpan>>& spans = spans_;
  std::vector<std::uint32_t>& found = last_found_;  // uncertain buildings found visible
  found.clear();
  for (const Swept& swept : order_) {
    pending.merge_nearer_than(swept.distance, horizon_, stats);
    const std::uint32_t b = swept.building;
    const Building& building = scene_.buildings[b];
    const DiscVertices* fixed = vertices_.data() + swept.vertices;
    auto span_of = [&](std::size_t p) {
      const std::vector<Vec2>& ring = building.prisms[p].ring;
      return span_from_tangents(ring.data(), ring.size(), fixed[p], e);
    };
    auto farthest_of = [&](std::size_t p) {
      const std::vector<Vec2>& ring = building.prisms[p].ring;
      return distance_to_vertex(ring.data(), ring.size(), fixed[p], e);
    };
    auto nearest_of = [&](std::size_t p) {
      const std::vector<Vec2>& ring = building.prisms[p].ring;
      return distance_to_edge(ring.data(), ring.size(), fixed[p], e);
    };
    if (current_->certainly_visible(b)) {
      queue_fixed_shadows(pending, building, fixed, eye, swept.distance, unclipped, horizon_.octant_boundaries(), farthest_of);
      continue;
    }
    ++stats.buildings_tested;
    if (!volume.may_intersect(building.bounds)) continue;
    // The box's bins without its span where box_outer_bins is certain of them (box_hidden),
    // which reads no tangent: span_from_tangents gives box_span's span bit for bit.
    if (box_hidden(horizon_, building.bounds.plan(), building.height, eye) ||
        !prisms_visible(horizon_, building, eye, spans, span_of, nearest_of, farthest_of))
      continue;
    found.push_back(b);
    queue_shadows(pending, ShadowRule::conservative, building, eye, swept.distance, unclipped, spans, farthest_of);
  }
  stats.horizon_nodes += horizon_.take_node_visits();
  stats.items_skipped = current_->visible().size() + current_->hidden_count();

  // The certainly visible, sorted with the certificate, merged with the few found visible.
  found_ids_.clear();
  for (std::uint32_t b : found) found_ids_.push_back(scene_.buildings[b].id);
  std::sort(found_ids_.begin(), found_ids_.end());
  result.pvs.resize(visible_ids_.size() + found_ids_.size());
  std::merge(visible_ids_.begin(), visible_ids_.end(), found_ids_.begin(), found_ids_.end(), result.pvs.begin());
  last_camera_ = camera;
  stats.cull_ms = ms_since(start);
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
  auto cast = [&](std::uint32_t b) {
    const Building& building = scene_.buildings[b];
    spans.clear();
    for (const ConvexVerticalPrism& prism : building.prisms) spans.push_back(convex_span(prism.ring, e));
    queue_shadows(shadows, ShadowRule::conservative, building, eye, min_distance(e, building.bounds.plan()), unclipped, spans);
  };
  // The last query's PVS: the certificate it used (current_ until the next query) and what it found.
  for (std::uint32_t b : current_->visible()) cast(b);
  for (std::uint32_t b : last_found_) cast(b);
  shadows.merge_all(final_, unused);
  return final_;
}

}  // namespace cullcheck
