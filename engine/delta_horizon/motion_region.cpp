#include "engine/delta_horizon/motion_region.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <queue>

#include "engine/horizon/horizon_sweep.hpp"
#include "engine/horizon/polar_geometry.hpp"

namespace cullcheck {
namespace {

constexpr double kAngleMargin = 1e-9;     // radians
constexpr double kRelativeMargin = 1e-9;  // on slopes and distances

double widen(double v) { return v + kRelativeMargin * (1.0 + std::abs(v)); }
double narrow(double v) { return v - kRelativeMargin * (1.0 + std::abs(v)); }

// Largest change of a point's azimuth, seen from an eye that moves by at most `radius` in plan,
// for a point at least `distance` away (distance > radius).
double azimuth_shift(double radius, double distance) {
  return std::asin(std::min(1.0, radius / distance)) + kAngleMargin;
}

AzimuthSpan widened(const AzimuthSpan& s, double by) {
  if (s.end - s.begin + 2 * by >= kTwoPi) return {0.0, kTwoPi, s.slack};
  return {s.begin - by, s.end + by, s.slack};
}

// One arc where two arcs overlap (either one when they overlap twice), or none.
std::optional<AzimuthSpan> overlap(const AzimuthSpan& a, const AzimuthSpan& b) {
  if (b.full_circle()) return a;
  if (a.full_circle()) return b;
  for (double shift : {-kTwoPi, 0.0, kTwoPi}) {
    const double lo = std::max(a.begin, b.begin + shift), hi = std::min(a.end, b.end + shift);
    if (lo < hi) return AzimuthSpan{lo, hi, std::max(a.slack, b.slack)};
  }
  return std::nullopt;
}

// Azimuths that every camera of the region covers (so OH(OS) never starts a bin touching them at
// +inf): those of the anchor's pyramid narrowed by k on every side. A direction inside the
// narrowed pyramid is at least asin(c sin k) from each original plane, c = min(cos(hfov/2),
// cos(vfov/2)) (its component across the plane is at least sin k times its component in the
// plane's pivot plane, which is at least c); k with c sin k > sin(turn) keeps it inside after
// any rotation by `turn`. Empty when nothing is left.
std::optional<AzimuthSpan> safe_coverage(const Camera& anchor, double turn) {
  if (anchor.omnidirectional()) return AzimuthSpan{0.0, kTwoPi};
  const double c = std::min(std::cos(anchor.hfov / 2), std::cos(anchor.vfov / 2));
  const double s = widen(std::sin(std::min(turn, kPi / 2)) / c);
  if (s >= 1.0) return std::nullopt;
  const double k = std::asin(s) + kAngleMargin;
  Camera narrowed = anchor;
  narrowed.hfov -= 2 * k;
  narrowed.vfov -= 2 * k;
  if (narrowed.hfov <= 0.0 || narrowed.vfov <= 0.0) return std::nullopt;
  const AzimuthSpan span = azimuth_coverage(narrowed);
  if (span.full_circle()) return span;
  if (span.end - span.begin <= 2 * kAngleMargin) return std::nullopt;
  return AzimuthSpan{span.begin + kAngleMargin, span.end - kAngleMargin};
}

// Region-wide bounds, from the anchor eye `a` (plan `a2`), plan radius ε and height ζ:
//  - plan distances move by at most ε (distance to a fixed set is 1-Lipschitz);
//  - azimuths of a point at distance r move by at most asin(ε / r);
//  - the eye's height lies in [a.z - ζ, a.z + ζ].
struct RegionBounds {
  Vec3 a;
  Vec2 a2;
  double eps, zeta;

  bool beyond_reach(double near) const { return narrow(near) > widen(eps); }

  // An item (a solid standing on the ground up to `top`, span `span` from a2, plan distances in
  // [near, far]): its span widened and its highest slope raised over the region. OH(OS)'s test
  // at any camera of the region reads no bin outside the widened span and compares a slope no
  // higher. Empty when the eye may come within the item's reach.
  std::optional<std::pair<AzimuthSpan, double>> grown_item(const AzimuthSpan& span, double top, double near,
                                                           double far) const {
    if (!beyond_reach(near)) return std::nullopt;
    return std::pair{widened(span, azimuth_shift(eps, narrow(near))), raised_slope(top, near, far)};
  }
  // The item's highest slope over the region (grown_item's and seen_item's); near beyond reach.
  double raised_slope(double top, double near, double far) const {
    const double rise = top - (a.z - zeta);
    return widen(rise >= 0.0 ? rise / (narrow(near) - widen(eps)) : rise / widen(far + eps));
  }

  // The same item for a test of what any eye of the region sees, not of OH(OS)'s decision there
  // (the certificate's true-visibility mode): its slope raised as grown_item's, its span narrowed
  // by target_span (engine/horizon/horizon_sweep.hpp) instead of widened. Its points at
  // distance R keep within asin(ε / R) of the shrunk shadows' narrowed spans, which puts them
  // inside each eye's shadow; OH(OS)'s own test at that eye would read the wider span.
  std::optional<std::pair<AzimuthSpan, double>> seen_item(const AzimuthSpan& span, double top, double near,
                                                          double far) const {
    if (!beyond_reach(near)) return std::nullopt;
    return std::pair{target_span(span, eps, widen(far)), raised_slope(top, near, far)};
  }

  // A CVP's highest slope, lowered to its minimum over the region, with its span narrowed: every
  // camera's span holds the narrowed one (see narrowed), and the CVP reaches at least
  // this slope over it. Empty when nothing is left.
  std::optional<std::pair<AzimuthSpan, double>> lowered_item(const std::vector<Vec2>& ring, const ConvexSpan& span,
                                                             double top, double near, double far) const {
    if (!beyond_reach(near) || !(narrow(far) > widen(eps))) return std::nullopt;
    const auto s = narrowed(ring, span);
    if (!s) return std::nullopt;
    const double rise = top - (a.z + zeta);
    const double slope = rise >= 0.0 ? rise / widen(near + eps) : rise / (narrow(far) - widen(eps));
    return std::pair{*s, narrow(slope)};
  }

  // A CVP's span as every camera of the region at least sees it: the tangent vertices seen from
  // a2 at azimuths b and e (distances r_b, r_e) move to b', e' within asin(ε / r) each; the CVP's
  // directions from any eye of the region form one arc shorter than half a turn holding b' and
  // e', which (as the arc from b to e widened by both shifts stays under half a turn) is the arc
  // from b' to e' and so holds [b + shift_b, e - shift_e]. Thesis Eq. 4-6 shrink by the same
  // angles; this is why they hold. Empty when nothing is left.
  std::optional<AzimuthSpan> narrowed(const std::vector<Vec2>& ring, const ConvexSpan& span) const {
    const double rb = length(ring[span.first_tangent] - a2), re = length(ring[span.last_tangent] - a2);
    if (!beyond_reach(rb) || !beyond_reach(re)) return std::nullopt;
    const double shift_b = azimuth_shift(eps, narrow(rb)), shift_e = azimuth_shift(eps, narrow(re));
    const AzimuthSpan s{span.span.begin + shift_b, span.span.end - shift_e, span.span.slack};
    if (!(s.end > s.begin) || !(span.span.end - span.span.begin + shift_b + shift_e < kPi - 1e-6)) return std::nullopt;
    return s;
  }

  // A CVP's shadow as every camera of the region at least casts it (OH(OS)'s conservative rule).
  // Empty when nothing is left, or when the CVP may come nearer than `unclipped` (it may then
  // not be used as an occluder, see horizon_sweep.hpp).
  // Span: see narrowed().
  // Slope: with the lowest rise r = height - (a.z + ζ): if r >= 0 the rule's value is at least
  // r over the farthest vertex distance (the tangent vertices are no farther), which is at most
  // max_vertex + ε; if r < 0, at least r over the far-chain distance, which is at least the
  // boundary distance, at least min_boundary - ε.
  std::optional<std::pair<AzimuthSpan, double>> shrunk_shadow(const ConvexVerticalPrism& prism, const ConvexSpan& span,
                                                              double min_boundary, double max_vertex,
                                                              double unclipped) const {
    if (!(narrow(min_boundary) - widen(eps) > widen(unclipped))) return std::nullopt;
    const auto s = narrowed(prism.ring, span);
    if (!s) return std::nullopt;
    const double rise = prism.height - (a.z + zeta);
    const double slope = rise >= 0.0 ? rise / widen(max_vertex + eps) : rise / (narrow(min_boundary) - widen(eps));
    if (!std::isfinite(slope)) return std::nullopt;  // degenerate geometry hides nothing
    return std::pair{*s, narrow(slope)};
  }

  // A CVP's shadow as no camera of the region casts it higher: the span widened, the slope at
  // its highest. With the highest rise r = height - (a.z - ζ): if r >= 0 the rule's value is at
  // most r over the nearest tangent-vertex distance, at least min_boundary - ε; if r < 0, at
  // most r over the far-chain distance, which is at most max_vertex + ε. A CVP the eye may reach
  // casts an unbounded shadow (+inf everywhere).
  std::pair<AzimuthSpan, double> grown_shadow(const ConvexVerticalPrism& prism, const std::optional<ConvexSpan>& span,
                                              double min_boundary, double max_vertex) const {
    if (!span || !beyond_reach(min_boundary)) return {{0.0, kTwoPi}, HUGE_VAL};
    const AzimuthSpan g = widened(span->span, azimuth_shift(eps, narrow(min_boundary)));
    const double rise = prism.height - (a.z - zeta);
    const double slope = rise >= 0.0 ? rise / (narrow(min_boundary) - widen(eps)) : rise / widen(max_vertex + eps);
    return {g, widen(slope)};
  }
};

// How far the box lies beyond the eye along each axis (0 where the eye is within its extent).
Vec3 box_offsets(const ViewVolume& volume, const Box3& box) {
  return {std::max({box.lo.x - volume.eye.x, 0.0, volume.eye.x - box.hi.x}),
          std::max({box.lo.y - volume.eye.y, 0.0, volume.eye.y - box.hi.y}),
          std::max({box.lo.z - volume.eye.z, 0.0, volume.eye.z - box.hi.z})};
}
// Distance from the eye to a box: the plain sum of squares (bit-identical to the rest of the
// engine), rescaled only when a square overflows, so that a box 1e200 m away is not "beyond
// far" because its distance came out +inf.
double box_distance(const ViewVolume& volume, const Box3& box) {
  const auto [dx, dy, dz] = box_offsets(volume, box);
  const double d2 = dx * dx + dy * dy + dz * dz;
  if (std::isfinite(d2)) return std::sqrt(d2);
  const double m = std::max({dx, dy, dz});
  if (!std::isfinite(m)) return m;
  const double x = dx / m, y = dy / m, z = dz / m;
  return m * std::sqrt(x * x + y * y + z * z);
}

double yaw_difference(double a, double b) { return std::abs(std::remainder(a - b, kTwoPi)); }

// What the sweep keeps about a building it could not mark hidden.
struct Candidate {
  std::uint32_t building;
  std::uint32_t first_prism;  // its CVPs' geometry in the sweep's prism list
  double nearest;           // plan distance of its box from the anchor
  double nearest_farthest;  // smallest farthest-vertex distance among its CVPs
  AzimuthSpan reach;        // its box's span widened for the region (covers every CVP's shadow)
};

}  // namespace

// Plane tests over the region's view volumes. For a camera of the region, a plane's normal n'
// is within `turn` of the anchor's n (|n' - n| <= turn) and its eye e' within `reach` of the
// anchor's a, so for any point p:
//   |(n'.(p - e') - k) - (n.(p - a) - k)| <= turn |p - a| + reach.
// certainly_meets: for every plane the box's deepest corner stays inside, so OH(OS) at any
// camera of the region does not cull the box by its view volume.
// may_meet: false only when for some plane the whole box stays outside for every camera.
bool certainly_meets(const ViewVolume& volume, const Box3& box, double reach, double turn) {
  if (volume.omnidirectional) return widen(box_distance(volume, box) + reach) < volume.far;
  for (int i = 0; i < volume.plane_count; ++i) {
    const Vec3& n = volume.planes[i].n;
    const Vec3 corner{n.x >= 0 ? box.hi.x : box.lo.x, n.y >= 0 ? box.hi.y : box.lo.y, n.z >= 0 ? box.hi.z : box.lo.z};
    if (narrow(volume.planes[i].signed_distance(corner)) < widen(turn * length(corner - volume.eye) + reach)) return false;
  }
  return true;
}
bool may_meet(const ViewVolume& volume, const Box3& box, double reach, double turn) {
  if (volume.omnidirectional) {
    // Most boxes lie far inside the far plane: their L1 distance, an upper bound of the distance
    // with room for rounding, settles it without the square root (same answer; NaN falls through).
    const Vec3 d = box_offsets(volume, box);
    if (d.x + d.y + d.z <= 0.5 * volume.far && reach >= 0.0) return true;
    return narrow(box_distance(volume, box) - reach) <= volume.far;
  }
  const double far_extent = length(Vec3{std::max(std::abs(box.lo.x - volume.eye.x), std::abs(box.hi.x - volume.eye.x)),
                                        std::max(std::abs(box.lo.y - volume.eye.y), std::abs(box.hi.y - volume.eye.y)),
                                        std::max(std::abs(box.lo.z - volume.eye.z), std::abs(box.hi.z - volume.eye.z))});
  for (int i = 0; i < volume.plane_count; ++i) {
    const Vec3& n = volume.planes[i].n;
    const Vec3 corner{n.x >= 0 ? box.hi.x : box.lo.x, n.y >= 0 ? box.hi.y : box.lo.y, n.z >= 0 ? box.hi.z : box.lo.z};
    if (widen(volume.planes[i].signed_distance(corner) + turn * far_extent + reach) < 0.0) return false;
  }
  return true;
}

// For a box inside `extent`, each of box_offsets' terms is at most the extent's farthest offset
// on that axis (max(lo - e, 0, e - hi) grows as lo rises and hi falls, and rounding keeps the
// order), and so is their rounded sum; so may_meet's L1 shortcut, taken here, holds for it too.
bool meets_every_box(const ViewVolume& volume, const Box3& extent, double reach) {
  if (!volume.omnidirectional || !(reach >= 0.0)) return false;
  const Vec3& e = volume.eye;
  const Vec3 far_corner{std::max({extent.hi.x - e.x, 0.0, e.x - extent.lo.x}), std::max({extent.hi.y - e.y, 0.0, e.y - extent.lo.y}),
                        std::max({extent.hi.z - e.z, 0.0, e.z - extent.lo.z})};
  return far_corner.x + far_corner.y + far_corner.z <= 0.5 * volume.far;
}

bool MotionRegion::contains(const Camera& c) const {
  const Camera& a = anchor;
  if (c.hfov != a.hfov || c.vfov != a.vfov || c.near != a.near || c.far != a.far) return false;
  if (length(plan(c.position) - plan(a.position)) > radius || std::abs(c.position.z - a.position.z) > height) return false;
  if (a.omnidirectional()) return true;
  return yaw_difference(c.yaw, a.yaw) + std::abs(c.pitch - a.pitch) + std::abs(c.roll - a.roll) <= turn;
}

RegionCertificate::RegionCertificate(const Scene& scene, const Quadtree& quadtree, std::uint32_t bins)
    : scene_(scene),
      quadtree_(quadtree),
      shrunk_(bins),
      grown_(bins),
      uncertain_reach_(bins),
      visible_epoch_(scene.buildings.size(), 0) {}

// The certificate sweep mirrors OH(OS)'s (horizon_sweep.hpp) from the anchor, with every bound
// taken over the region. Why each class is right, for any camera of the region:
//  - hidden: the item's widened span and raised slope lie below the shrunk horizon, so OH(OS)'s
//    own test (span inside the widened one, slope below the raised one, horizon at least the
//    shrunk one on every bin) culls it. A shadow enters the shrunk horizon only after the sweep
//    (by anchor distance) has passed its CVP's farthest point + 2ε: from any eye of the region
//    that point is then nearer than the item, so OH(OS) has merged the shadow before the test.
//    Shadows come from every unmarked building whose box certainly meets every view volume of
//    the region: OH(OS) tests it, and either merges its shadows or finds it hidden, in which
//    case its shadows lie below a horizon that is already there.
//  - visible: it certainly meets the view volume, and some CVP's lowered slope reaches the
//    grown horizon at a bin of its narrowed span that every camera's coverage touches. OH(OS)'s
//    horizon at that CVP's test holds only shadows of buildings it tests (never of marked-hidden
//    or certainly-outside ones) whose farthest point is nearer than it; each of those is in the
//    grown horizon, whose shadows are merged once the sweep passes farthest - 2ε, and the
//    decision waits until the sweep has passed the building's nearest point + 2ε.
//  - relevant: an uncertain building X is decided by OH(OS)'s test against the shadows that
//    reach the bins X's test reads and are merged before that test; a certainly visible building
//    can cast one only if its widened span meets X's and one of its CVPs' farthest point - 2ε
//    lies before X's nearest point, and then it is swept.
// So a query that sweeps only the uncertain and relevant buildings decides each uncertain one
// exactly as OH(OS) does, and the PVS is those plus the certainly visible.
void RegionCertificate::certify(const MotionRegion& region, CullStatistics& stats, bool same_as_oh_os, bool narrow_targets) {
  if (++epoch_ == 0) {
    std::fill(visible_epoch_.begin(), visible_epoch_.end(), 0);
    epoch_ = 1;
  }
  visible_.clear();
  swept_.clear();
  hidden_count_ = uncertain_count_ = 0;
  const Camera& camera = region.anchor;
  const ViewVolume volume(camera);
  const RegionBounds bounds{camera.position, plan(camera.position), region.radius, region.height};
  const double reach = std::hypot(region.radius, region.height);
  const double unclipped = unclipped_distance(camera);
  const std::optional<AzimuthSpan> covered = safe_coverage(camera, region.turn);
  const Vec2 e = bounds.a2;
  const double two_eps = 2 * region.radius;
  shrunk_.reset();
  grown_.reset();
  uncertain_reach_.reset();
  shrunk_.take_node_visits();
  grown_.take_node_visits();
  uncertain_reach_.take_node_visits();

  QuadHeap<SweepItem> sweep;
  ShadowQueue pending_shrunk, pending_grown;
  std::vector<Candidate> candidates;
  // Visibility decisions wait until the sweep passes nearest + 2ε: (key, candidate index).
  std::priority_queue<std::pair<double, std::size_t>, std::vector<std::pair<double, std::size_t>>, std::greater<>> decisions;
  std::vector<std::uint8_t> decided_visible;
  const auto& cells = quadtree_.cells();
  if (!cells.empty() && cells[0].last > cells[0].first) sweep.push({min_distance(e, cells[0].bounds), false, 0});

  // An item's span and slope for the hidden test: OH(OS)'s at every camera, or what every eye sees.
  auto tested = [&](const AzimuthSpan& span, double top, double near, double far) {
    return same_as_oh_os || !narrow_targets ? bounds.grown_item(span, top, near, far) : bounds.seen_item(span, top, near, far);
  };
  auto hidden_box = [&](const Box2& box, double top) {
    const auto span = box_span(box, e);
    if (!span) return false;
    const auto g = tested(span->span, top, min_distance(e, box), max_distance(e, box));
    return g && shrunk_.hides(g->first, g->second);
  };
  // The CVPs of every candidate seen from the anchor (computed once, read again by decide).
  struct PrismView {
    std::optional<ConvexSpan> span;
    double near, far;
  };
  std::vector<PrismView> prism_views;
  auto decide = [&](std::size_t i) {
    const Building& building = scene_.buildings[candidates[i].building];
    bool visible = false;
    if (covered && certainly_meets(volume, building.bounds, reach, region.turn)) {
      for (std::size_t p = 0; p < building.prisms.size(); ++p) {
        const PrismView& view = prism_views[candidates[i].first_prism + p];
        if (!view.span) continue;
        const auto low = bounds.lowered_item(building.prisms[p].ring, *view.span, building.prisms[p].height, view.near, view.far);
        if (!low) continue;
        const auto bins = overlap(low->first, *covered);
        if (bins && grown_.min_over(*bins) <= low->second) {
          visible = true;
          break;
        }
      }
    }
    decided_visible[i] = visible;
    // Two bins wider: the raise fills only bins wholly inside, and must cover every bin the
    // building's own test may read.
    if (!visible) uncertain_reach_.raise(widened(candidates[i].reach, 2 * shrunk_.bin_width()), candidates[i].nearest);
  };
  // Each decision at key k sees the grown shadows keyed below k, and only those: a candidate Y
  // whose shadow OH(OS) may merge before X's test from some eye of the region has far_Y - 2ε <
  // nearest_X, so its key is below X's, and Y was swept before the sweep passed X's key. Merging
  // up to the next item instead (as this did before) took in shadows that depend on which cells
  // and buildings happen to be swept in between: a sharper cell test then left fewer buildings
  // certainly visible.
  auto decide_before = [&](double distance) {
    while (!decisions.empty() && decisions.top().first < distance) {
      pending_grown.merge_nearer_than(decisions.top().first, grown_, stats);
      decide(decisions.top().second);
      decisions.pop();
    }
    pending_grown.merge_nearer_than(distance, grown_, stats);
  };

  std::vector<std::optional<ConvexSpan>> spans;
  while (!sweep.empty()) {
    const SweepItem item = sweep.top();
    sweep.pop();
    pending_shrunk.merge_nearer_than(item.distance, shrunk_, stats);
    decide_before(item.distance);
    if (!item.is_building) {
      const Quadtree::Cell& cell = cells[item.index];
      ++stats.cells_tested;
      const Box3 box{{cell.bounds.lo.x, cell.bounds.lo.y, 0.0}, {cell.bounds.hi.x, cell.bounds.hi.y, cell.max_height}};
      if (!may_meet(volume, box, reach, region.turn)) continue;
      // Both boxes of the cell's height split (as cell_hidden, engine/horizon/horizon_sweep.hpp).
      if (hidden_box(cell.tall_bounds, cell.max_height) && (!cell.has_rest() || hidden_box(cell.bounds, cell.rest_height))) {
        hidden_count_ += cell.last - cell.first;
        continue;
      }
      quadtree_.for_each_child(
          cell, [&](std::uint32_t c) { sweep.push({min_distance(e, cells[c].bounds), false, c}); },
          [&](std::uint32_t b) { sweep.push({min_distance(e, scene_.buildings[b].bounds.plan()), true, b}); });
      continue;
    }
    const Building& building = scene_.buildings[item.index];
    ++stats.buildings_tested;
    if (!may_meet(volume, building.bounds, reach, region.turn)) continue;
    spans.clear();
    bool hidden = hidden_box(building.bounds.plan(), building.height);
    for (const ConvexVerticalPrism& prism : building.prisms) spans.push_back(convex_span(prism.ring, e));
    if (!hidden) {
      hidden = true;
      for (std::size_t p = 0; p < building.prisms.size() && hidden; ++p) {
        const ConvexVerticalPrism& prism = building.prisms[p];
        const auto g = spans[p] ? tested(spans[p]->span, prism.height, min_boundary_distance(prism.ring, e),
                                         max_vertex_distance(prism.ring, e))
                                : std::nullopt;
        hidden = g && shrunk_.hides(g->first, g->second);
      }
    }
    if (hidden) {
      ++hidden_count_;
      continue;
    }
    // A candidate: its shadows bound the horizon from below (if OH(OS) surely tests it) and
    // from above, and its own visibility is decided once the sweep is 2ε past it.
    const bool surely_tested = !same_as_oh_os || certainly_meets(volume, building.bounds, reach, region.turn);
    double nearest_farthest = HUGE_VAL;
    const auto first_prism = static_cast<std::uint32_t>(prism_views.size());
    for (std::size_t p = 0; p < building.prisms.size(); ++p) {
      const ConvexVerticalPrism& prism = building.prisms[p];
      const double near = min_boundary_distance(prism.ring, e), far = max_vertex_distance(prism.ring, e);
      prism_views.push_back({spans[p], near, far});
      nearest_farthest = std::min(nearest_farthest, far);
      const auto up = bounds.grown_shadow(prism, spans[p], near, far);
      pending_grown.push(narrow(far - two_eps), up.first, up.second);
      if (!surely_tested || !spans[p]) continue;
      const auto low = bounds.shrunk_shadow(prism, *spans[p], near, far, unclipped);
      if (low) pending_shrunk.push(widen(far + two_eps), low->first, low->second);
    }
    const auto box = box_span(building.bounds.plan(), e);
    const AzimuthSpan reach_span =
        box && bounds.beyond_reach(item.distance) ? widened(box->span, azimuth_shift(region.radius, narrow(item.distance)))
                                                  : AzimuthSpan{0.0, kTwoPi};
    candidates.push_back({item.index, first_prism, item.distance, nearest_farthest, reach_span});
    decided_visible.push_back(0);
    decisions.push({widen(item.distance + two_eps), candidates.size() - 1});
  }
  decide_before(HUGE_VAL);

  for (std::size_t i = 0; i < candidates.size(); ++i) {
    const Candidate& c = candidates[i];
    if (!decided_visible[i]) {
      swept_.push_back(c.building);
      ++uncertain_count_;
      continue;
    }
    visible_.push_back(c.building);
    visible_epoch_[c.building] = epoch_;
    // Relevant when some uncertain building whose widened span meets this one's lies beyond
    // this one's nearest CVP farthest point - 2ε.
    if (uncertain_reach_.max_over(c.reach) > narrow(c.nearest_farthest - two_eps)) swept_.push_back(c.building);
  }
  std::sort(visible_.begin(), visible_.end());
  stats.horizon_nodes += shrunk_.take_node_visits() + grown_.take_node_visits() + uncertain_reach_.take_node_visits();
}

}  // namespace cullcheck
