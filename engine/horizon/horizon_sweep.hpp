// The front-to-back sweep of OH(OS) and the from-region shrinking methods, and the tests and
// shadow queue the guarded ΔH reuses (thesis ch. 3.1.1-3.1.2).
//
// One query: the horizon starts empty except outside the view volume's azimuth coverage; the
// quadtree is traversed best-first on the cells' and buildings' nearest plan distance; a cell or
// building is culled when it lies outside the view volume or its highest slope over its azimuth
// span is below min H there. A building that survives is in the PVS and its CVPs' shadows wait
// in a ShadowQueue until the sweep has passed the CVP's farthest point (Downs et al.'s "update
// OH at its maximum distance"), so whatever is tested against H lies wholly behind every shadow
// in H. When the sweep ends, the shadows still waiting are merged too, so the final horizon is
// the maximum over every visible building's shadows: a well-defined H(t) for ΔH to carry over.
//
// What the PVS is, independent of traversal order (ΔH's exactness argument rests on it): a
// building b is in the PVS iff its box meets the view volume and neither its box nor all of its
// CVPs are hidden by H_<d(b) = the maximum of the shadows of PVS members whose CVP's farthest
// point is nearer than b's nearest point d(b). A hidden building's shadows would change nothing
// (its shadow is never above the horizon that hid it), so skipping a building that is known to
// be hidden — without testing it — gives the same PVS and the same horizon.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>
#include <vector>

#include "core/camera.hpp"
#include "core/scene.hpp"
#include "engine/horizon/occlusion_horizon.hpp"
#include "engine/horizon/polar_geometry.hpp"
#include "engine/horizon/quad_heap.hpp"
#include "engine/method.hpp"
#include "engine/spatial/quadtree.hpp"

namespace cullcheck {

// Which elevation a CVP's shadow gets (see object_space_horizon.hpp).
enum class ShadowRule { thesis, conservative };

// Slope of a CVP's shadow under `rule`, given its span seen from the eye.
double shadow_slope(ShadowRule rule, const ConvexVerticalPrism& prism, Vec3 eye, const ConvexSpan& span);

// Geometry nearer than the near plane is clipped and hides nothing. A point of the view volume
// lies at least `near` deep, so at least near / cos(corner angle) from the eye; a CVP whose plan
// distance is below this may be partly clipped and is not used as an occluder.
double unclipped_distance(const Camera& camera);

// One CVP's shadow: merged into H once the sweep has passed `farthest` (the CVP's farthest plan
// distance, or later where a method delays it).
struct Shadow {
  double farthest;
  AzimuthSpan span;  // rounded inward by the horizon, unless `by_bins`
  double slope;
  // With `by_bins`, that rounding itself (span_inner_bins, box_bins.hpp, where a caller found it
  // without the span): bins first_bin .. last_bin of a horizon with as many bins as the one it
  // was found for (every horizon of a method has MethodOptions::horizon_bins). Below 2^21.
  std::int32_t first_bin = 0, last_bin = -1;
  bool by_bins = false;

  static Shadow of_bins(double farthest, const BinRange& bins, double slope) {
    return {farthest, AzimuthSpan{}, slope, std::int32_t(bins.first), std::int32_t(bins.last), true};
  }
  void raise(OcclusionHorizon& horizon, double at_slope) const {
    if (by_bins)
      horizon.raise_range({first_bin, last_bin}, at_slope);
    else
      horizon.raise(span, at_slope);
  }
};

// Shadows waiting until the sweep passes their CVP's farthest point; merged in that order.
// With record_into, every shadow pushed is also appended to a log, so that a second sweep over
// other objects (passive targets, engine/shrinking/passive_targets.hpp) can meet the same
// horizon at the same distances by pushing the log again.
class ShadowQueue {
 public:
  void clear() {
    queue_.clear();
    order_ = 0;
    replay_.clear();
    replay_next_ = 0;
  }
  void record_into(std::vector<Shadow>* log) { log_ = log; }
  void push(double farthest, const AzimuthSpan& span, double slope) { push(Shadow{farthest, span, slope}); }
  // A shadow whose inner rounding is known (span_inner_bins): its span is never read.
  void push(double farthest, const BinRange& bins, double slope) { push(Shadow::of_bins(farthest, bins, slope)); }
  void push(const Shadow& shadow) {
    queue_.push({shadow, order_++});
    if (log_) log_->push_back(shadow);
  }
  // Queues a whole log at once (a passive-target sweep replaying a building sweep's shadows):
  // sorted once by farthest point instead of pushed one by one. Merging is a maximum, so the
  // order among shadows of equal distance changes nothing.
  void replay(const std::vector<Shadow>& log) {
    replay_.assign(log.begin(), log.end());
    std::sort(replay_.begin(), replay_.end(), [](const Shadow& a, const Shadow& b) { return a.farthest < b.farthest; });
    replay_next_ = 0;
  }
  // Merges every shadow whose farthest point is nearer than `distance` (strictly) into `horizon`
  // and, when given, into `also` (ΔH raises H(t+1) and its mask together).
  void merge_nearer_than(double distance, OcclusionHorizon& horizon, CullStatistics& stats,
                         OcclusionHorizon* also = nullptr) {
    auto merge = [&](const Shadow& shadow) {
      shadow.raise(horizon, shadow.slope);
      if (also) shadow.raise(*also, shadow.slope);
      ++stats.occluders_applied;
    };
    for (; replay_next_ < replay_.size() && replay_[replay_next_].farthest < distance; ++replay_next_) merge(replay_[replay_next_]);
    for (; !queue_.empty() && queue_.top().shadow.farthest < distance; queue_.pop()) merge(queue_.top().shadow);
  }
  void merge_all(OcclusionHorizon& horizon, CullStatistics& stats, OcclusionHorizon* also = nullptr) {
    merge_nearer_than(HUGE_VAL, horizon, stats, also);
  }

 private:
  struct Pending {
    Shadow shadow;
    std::uint64_t order;  // insertion order, for a deterministic tie-break
    bool operator>(const Pending& o) const {
      return shadow.farthest != o.shadow.farthest ? shadow.farthest > o.shadow.farthest : order > o.order;
    }
  };
  QuadHeap<Pending> queue_;
  std::uint64_t order_ = 0;
  std::vector<Shadow>* log_ = nullptr;
  std::vector<Shadow> replay_;  // sorted by farthest; merged from replay_next_ on
  std::size_t replay_next_ = 0;
};

// One entry of the front-to-back sweep: a quadtree cell or a building, keyed by its nearest plan
// distance; ties broken by kind and index so that the order is deterministic.
struct SweepItem {
  double distance;
  bool is_building;
  std::uint32_t index;  // cell index, or scene building index
  bool operator>(const SweepItem& o) const {
    if (distance != o.distance) return distance > o.distance;
    if (is_building != o.is_building) return is_building > o.is_building;
    return index > o.index;
  }
};

// The span a from-region sweep tests a target by (engine/shrinking/region_sweep.hpp): for shadows
// narrowed by asin(ε / r) at a tangent vertex r away (the sight line from the disc's edge, taken
// at its limit direction), a target point X at distance R from the centre is hidden by that
// shadow if its azimuth lies within asin(ε / R) outside it: the umbra's edge is the line through
// the vertex tangent to the disc, which at distance R lies that much outside the limit direction.
// So a target whose points all lie within `farthest` is tested by its span narrowed by
// asin(ε / farthest) at each end (to its middle when less is left). Along a street, where the
// facades' setbacks decide what shows past the nearer ones, this is about ε of lateral room at
// the target. `margin` ε = 0 (OH(OS)'s own sweeps) or a target within 2ε: the span unchanged.
inline AzimuthSpan target_span(const AzimuthSpan& span, double margin, double farthest) {
  if (!(margin > 0.0) || !(farthest > 2 * margin) || span.full_circle()) return span;
  // A hair less than asin's value, so that its rounding never narrows too much.
  const double by = std::asin(margin / farthest) * (1.0 - 1e-12);
  AzimuthSpan out = span;
  out.begin += by, out.end -= by;
  if (out.begin > out.end) out.begin = out.end = span.begin + (span.end - span.begin) / 2;
  return out;
}

// OH(OS)'s tests, shared by every sweep that uses them:
// a box (cell or building bounds, standing on the ground up to `top`) is hidden when its highest
// slope lies below the horizon over its azimuth span; a box that contains the eye is not.
// `span` is box_span(box, plan(eye)), however the caller found it. `margin`: target_span's.
// `Horizon` is an OcclusionHorizon, or anything that answers hides(span, slope) as it would (the
// passive targets' test without the sweep's order, engine/shrinking/passive_targets.cpp).
template <class Horizon>
bool box_hidden(Horizon& horizon, const std::optional<ConvexSpan>& span, const Box2& box, double top, Vec3 eye,
                double margin = 0.0) {
  if (!span) return false;
  const Vec2 e = plan(eye);
  const double farthest = max_distance(e, box);
  return horizon.hides(target_span(span->span, margin, farthest), max_slope(top, eye.z, min_distance(e, box), farthest));
}
template <class Horizon>
bool box_hidden(Horizon& horizon, const Box2& box, double top, Vec3 eye, double margin = 0.0) {
  const Vec2 e = plan(eye);
  // OH(OS)'s test reads the bins of the box's span, not the span: box_outer_bins gives those
  // bins without atan2 wherever they are certain (issue 17), the span gives them elsewhere. For
  // any horizon that also answers over bins already rounded.
  if constexpr (requires { horizon.hides_range(BinRange{}, 0.0); horizon.octant_boundaries(); }) {
    if (margin == 0.0)
      if (const auto bins = box_outer_bins(box, e, horizon.octant_boundaries()))
        return horizon.hides_range(*bins, max_slope(top, eye.z, min_distance(e, box), max_distance(e, box)));
  }
  return box_hidden(horizon, box_span(box, e), box, top, eye, margin);
}
// A quadtree cell is hidden when both boxes of its height split are (Quadtree::Cell): its tall
// buildings' box up to the tallest, and the whole cell up to the others' height. Sharper than
// the whole cell up to the tallest, and as conservative: every building lies in one of them.
template <class Horizon>
bool cell_hidden(Horizon& horizon, const Quadtree::Cell& cell, Vec3 eye, double margin = 0.0) {
  return box_hidden(horizon, cell.tall_bounds, cell.max_height, eye, margin) &&
         (!cell.has_rest() || box_hidden(horizon, cell.bounds, cell.rest_height, eye, margin));
}
// A building whose box is not hidden is visible unless every CVP is hidden; `spans` receives
// each CVP's span for its shadows.
// `span_of(p)`, `nearest_of(p)` and `farthest_of(p)` are convex_span, min_boundary_distance and
// max_vertex_distance of CVP p from the eye, however the caller finds them (the guarded ΔH reads
// them off vertices fixed for its region).
template <class Horizon, class SpanOf, class NearestOf, class FarthestOf>
bool prisms_visible(Horizon& horizon, const Building& building, Vec3 eye,
                    std::vector<std::optional<ConvexSpan>>& spans, const SpanOf& span_of, const NearestOf& nearest_of,
                    const FarthestOf& farthest_of, double margin = 0.0) {
  spans.clear();
  bool visible = false;
  for (std::size_t p = 0; p < building.prisms.size(); ++p) {
    spans.push_back(span_of(p));
    const auto& span = spans.back();
    if (visible || !span) {
      visible = true;
      continue;
    }
    const double farthest = farthest_of(p);
    visible = !horizon.hides(target_span(span->span, margin, farthest),
                             max_slope(building.prisms[p].height, eye.z, nearest_of(p), farthest));
  }
  return visible;
}
template <class Horizon>
bool prisms_visible(Horizon& horizon, const Building& building, Vec3 eye, std::vector<std::optional<ConvexSpan>>& spans,
                    double margin = 0.0) {
  const Vec2 e = plan(eye);
  return prisms_visible(
      horizon, building, eye, spans, [&](std::size_t p) { return convex_span(building.prisms[p].ring, e); },
      [&](std::size_t p) { return min_boundary_distance(building.prisms[p].ring, e); },
      [&](std::size_t p) { return max_vertex_distance(building.prisms[p].ring, e); }, margin);
}
// Whether a shadow computed from geometry may be merged: a NaN or infinite slope (or distance)
// comes from degenerate input (overflowing coordinates, a zero distance) and must hide nothing.
inline bool usable_shadow(double farthest, double slope) { return std::isfinite(farthest) && std::isfinite(slope); }

// Queues the shadow of CVP `p` of a visible building, whose span is `span` (shadow_slope reads
// its tangents only), filed under `at`: the span's azimuths, or the bins raise() would round them
// to (ShadowQueue::push takes either). None when the CVP may reach in front of the near plane
// (`may_be_clipped`: the building's nearest distance is below `unclipped`) or the shadow is not
// usable_shadow. `farthest_of(p)` is max_vertex_distance of the CVP from the eye.
template <class At, class FarthestOf>
inline void queue_prism_shadow(ShadowQueue& pending, ShadowRule rule, const ConvexVerticalPrism& prism, std::size_t p,
                               Vec3 eye, bool may_be_clipped, double unclipped, const ConvexSpan& span, const At& at,
                               const FarthestOf& farthest_of) {
  if (may_be_clipped && min_boundary_distance(prism.ring, plan(eye)) < unclipped) return;
  const double farthest = farthest_of(p), slope = shadow_slope(rule, prism, eye, span);
  if (usable_shadow(farthest, slope)) pending.push(farthest, at, slope);
}

// Queues a visible building's shadows (queue_prism_shadow for each CVP that has a span; one that
// holds the eye has none and casts none). `distance` is its nearest plan distance.
template <class FarthestOf>
void queue_shadows(ShadowQueue& pending, ShadowRule rule, const Building& building, Vec3 eye, double distance,
                   double unclipped, const std::vector<std::optional<ConvexSpan>>& spans, const FarthestOf& farthest_of) {
  const bool may_be_clipped = distance < unclipped;
  for (std::size_t p = 0; p < building.prisms.size(); ++p)
    if (spans[p])
      queue_prism_shadow(pending, rule, building.prisms[p], p, eye, may_be_clipped, unclipped, *spans[p], spans[p]->span,
                         farthest_of);
}
inline void queue_shadows(ShadowQueue& pending, ShadowRule rule, const Building& building, Vec3 eye, double distance,
                          double unclipped, const std::vector<std::optional<ConvexSpan>>& spans) {
  const Vec2 e = plan(eye);
  queue_shadows(pending, rule, building, eye, distance, unclipped, spans,
                [&](std::size_t p) { return max_vertex_distance(building.prisms[p].ring, e); });
}

// Runs one query into `result` (PVS unsorted, statistics without cull_ms). What varies between
// the sweeps built on it:
//  - `restrict_to_coverage`: start bins outside the camera's azimuth coverage at +inf (OH(OS));
//    the from-region sweeps (engine/shrinking/) keep the full circle;
//  - `meets(volume, box)`: whether a box may be seen, so is not culled by the view volume;
//  - `cast(pending, building index, eye, nearest distance, unclipped, spans)`: queues the
//    shadows of a visible building (OH(OS): queue_shadows; shrinking: shrunk shadows);
//  - `known(building index)`: a building the caller already holds in its PVS (a view cell's
//    union of sample PVSs, engine/shrinking/view_cell.hpp) is accepted without its horizon tests
//    and casts its shadows. That changes nothing else: had it been hidden, each of its CVPs lay
//    below H over its span, and a shadow is never above the CVP's own highest slope over a span
//    within the CVP's (shrunk shadows even less), so merging it raises no bin. With a
//    `target_margin` the CVP lay below H over its span narrowed by asin(ε / farthest), and a
//    shadow shrunk at its tangent vertices (no farther) is narrowed at least that much.
//  - `pending`: the queue shadows wait in. It may arrive holding shadows already (a passive-
//    target sweep replays a building sweep's shadows); whatever is left is merged at the end.
//  - `leave_out(is_building, index)`: a cell or building the caller does not need to see at all,
//    not even queued. Only for things that cast no shadows (passive targets already held: what
//    they would add is known, and they hide nothing), so the rest of the sweep is unchanged.
//  - `cast_reads_spans`: false when `cast` ignores the spans (methods whose shadows come from
//    occluders shrunk beforehand): a known building's CVP spans are then not computed at all.
//  - `target_margin`: target_span's ε for the cells and buildings tested (0: OH(OS)'s tests).
//  - `finish_horizon`: merge the shadows still waiting when the sweep ends, so that the horizon
//    is the H(t) ΔH carries over; false for a sweep whose horizon nothing reads afterwards (the
//    from-region sweeps: those shadows lie behind everything tested, issue 17's VbAoI graph).
template <class Meets, class CastShadows, class Known, class LeaveOut>
void sweep_horizon(const Scene& scene, const Quadtree& quadtree, OcclusionHorizon& horizon, const Camera& camera,
                   bool restrict_to_coverage, const Meets& meets, const CastShadows& cast, const Known& known,
                   const LeaveOut& leave_out, ShadowQueue& pending, CullResult& result, bool cast_reads_spans = true,
                   double target_margin = 0.0, bool finish_horizon = true) {
  CullStatistics& stats = result.stats;
  const ViewVolume volume(camera);
  const Vec3 eye = camera.position;
  const Vec2 e = plan(eye);
  const double unclipped = unclipped_distance(camera);
  horizon.reset();
  if (restrict_to_coverage) horizon.restrict_to(azimuth_coverage(camera));
  horizon.take_node_visits();

  QuadHeap<SweepItem> sweep;
  std::vector<std::optional<ConvexSpan>> spans;
  const auto& cells = quadtree.cells();
  if (!cells.empty() && cells[0].last > cells[0].first && !leave_out(false, 0u))
    sweep.push({min_distance(e, cells[0].bounds), false, 0});

  while (!sweep.empty()) {
    const SweepItem item = sweep.top();
    sweep.pop();
    pending.merge_nearer_than(item.distance, horizon, stats);
    if (!item.is_building) {
      const Quadtree::Cell& cell = cells[item.index];
      ++stats.cells_tested;
      const Box3 box{{cell.bounds.lo.x, cell.bounds.lo.y, 0.0}, {cell.bounds.hi.x, cell.bounds.hi.y, cell.max_height}};
      if (!meets(volume, box) || cell_hidden(horizon, cell, eye, target_margin)) continue;
      quadtree.for_each_child(
          cell,
          [&](std::uint32_t c) {
            if (!leave_out(false, c)) sweep.push({min_distance(e, cells[c].bounds), false, c});
          },
          [&](std::uint32_t b) {
            if (!leave_out(true, b)) sweep.push({min_distance(e, scene.buildings[b].bounds.plan()), true, b});
          });
      continue;
    }
    const Building& building = scene.buildings[item.index];
    if (known(item.index)) {
      if (!meets(volume, building.bounds)) continue;
      ++stats.items_skipped;
      spans.clear();
      if (cast_reads_spans)
        for (const ConvexVerticalPrism& prism : building.prisms) spans.push_back(convex_span(prism.ring, e));
    } else {
      ++stats.buildings_tested;
      if (!meets(volume, building.bounds) || box_hidden(horizon, building.bounds.plan(), building.height, eye, target_margin) ||
          !prisms_visible(horizon, building, eye, spans, target_margin))
        continue;
    }
    result.pvs.push_back(building.id);
    cast(pending, item.index, eye, item.distance, unclipped, spans);
  }
  if (finish_horizon) pending.merge_all(horizon, stats);
  stats.horizon_nodes = horizon.take_node_visits();
}
template <class Meets, class CastShadows, class Known>
void sweep_horizon(const Scene& scene, const Quadtree& quadtree, OcclusionHorizon& horizon, const Camera& camera,
                   bool restrict_to_coverage, const Meets& meets, const CastShadows& cast, const Known& known,
                   ShadowQueue& pending, CullResult& result) {
  sweep_horizon(scene, quadtree, horizon, camera, restrict_to_coverage, meets, cast, known,
                [](bool, std::uint32_t) { return false; }, pending, result);
}
template <class Meets, class CastShadows>
void sweep_horizon(const Scene& scene, const Quadtree& quadtree, OcclusionHorizon& horizon, const Camera& camera,
                   bool restrict_to_coverage, const Meets& meets, const CastShadows& cast, CullResult& result) {
  ShadowQueue pending;
  sweep_horizon(scene, quadtree, horizon, camera, restrict_to_coverage, meets, cast,
                [](std::uint32_t) { return false; }, pending, result);
}

// Plain OH(OS) at one camera with `rule`'s shadows.
inline void sweep_horizon(const Scene& scene, const Quadtree& quadtree, OcclusionHorizon& horizon, ShadowRule rule,
                          const Camera& camera, CullResult& result) {
  sweep_horizon(
      scene, quadtree, horizon, camera, /*restrict_to_coverage=*/true,
      [](const ViewVolume& volume, const Box3& box) { return volume.may_intersect(box); },
      [&](ShadowQueue& pending, std::uint32_t index, Vec3 eye, double distance, double unclipped,
          const std::vector<std::optional<ConvexSpan>>& spans) {
        queue_shadows(pending, rule, scene.buildings[index], eye, distance, unclipped, spans);
      },
      result);
}

}  // namespace cullcheck
