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

// A box certainly meets the view volume of every camera of the region: for each plane of the
// anchor's volume, the corner that lies deepest inside stays inside when the plane's normal
// turns by at most `turn` (|Δn| <= turn) and the eye moves by at most `reach`:
//   n'.(c - e') - k >= n.(c - a) - k - turn |c - a| - reach.
// Then OH(OS) at any camera of the region tests the box's building instead of culling it by the
// view volume, so its shadows (or a horizon that already hides them) are there.
bool certainly_meets(const ViewVolume& volume, const Box3& box, double reach, double turn) {
  if (volume.omnidirectional) {
    // Inside the sphere of radius `far` for every eye: the nearest point plus the reach.
    const double dx = std::max({box.lo.x - volume.eye.x, 0.0, volume.eye.x - box.hi.x});
    const double dy = std::max({box.lo.y - volume.eye.y, 0.0, volume.eye.y - box.hi.y});
    const double dz = std::max({box.lo.z - volume.eye.z, 0.0, volume.eye.z - box.hi.z});
    return widen(std::sqrt(dx * dx + dy * dy + dz * dz) + reach) < volume.far;
  }
  for (int i = 0; i < volume.plane_count; ++i) {
    const Vec3& n = volume.planes[i].n;
    const Vec3 corner{n.x >= 0 ? box.hi.x : box.lo.x, n.y >= 0 ? box.hi.y : box.lo.y, n.z >= 0 ? box.hi.z : box.lo.z};
    const double slack = turn * length(corner - volume.eye) + reach;
    if (narrow(volume.planes[i].signed_distance(corner)) < widen(slack)) return false;
  }
  return true;
}

// Region-wide bounds, from the anchor eye `a` (plan `a2`), plan radius ε and height ζ:
//  - plan distances move by at most ε (distance to a fixed set is 1-Lipschitz);
//  - azimuths of a point at distance r move by at most asin(ε / r);
//  - the eye's height lies in [a.z - ζ, a.z + ζ].
struct RegionBounds {
  Vec3 a;
  Vec2 a2;
  double eps, zeta;

  // Widened span and raised highest slope of a solid standing on the ground up to `top`, whose
  // span from a2 is `span` and whose plan distances from a2 lie in [near, far]; empty when the
  // eye may come within the solid's reach (such an item is never certified).
  std::optional<std::pair<AzimuthSpan, double>> grown(const AzimuthSpan& span, double top, double near, double far) const {
    if (!(narrow(near) > widen(eps))) return std::nullopt;
    const double shift = azimuth_shift(eps, narrow(near));
    AzimuthSpan g{span.begin - shift, span.end + shift};
    if (g.end - g.begin >= kTwoPi) g = {0.0, kTwoPi};
    // Highest slope over the region: rise from the lowest eye, over the nearest (rising) or
    // farthest (falling) distance the region allows.
    const double rise = top - (a.z - zeta);
    const double slope = rise >= 0.0 ? rise / (narrow(near) - widen(eps)) : rise / widen(far + eps);
    return std::pair{g, widen(slope)};
  }

  // A CVP's shadow as every camera of the region at least casts it (OH(OS)'s conservative rule):
  // its span narrowed by the azimuth shift on both sides, the elevation lowered to its minimum.
  // Empty when nothing is left, or when the CVP may come nearer than `unclipped` (it may then
  // not be used as an occluder, see horizon_sweep.hpp).
  //
  // Span: the tangent points seen from a2 at azimuths b and e move to b', e' within `shift`; the
  // CVP's directions from any eye of the region form one arc shorter than half a turn holding
  // b' and e', which (as e - b + 2 shift < pi) is the arc from b' to e' and so holds
  // [b + shift, e - shift].
  // Slope: with the lowest rise r = height - (a.z + ζ): if r >= 0 the rule's value is at least
  // r over the farthest vertex distance (the tangent vertices are no farther), which is at most
  // max_vertex + ε; if r < 0, at least r over the far-chain distance, which is at least the
  // boundary distance, at least min_boundary - ε.
  std::optional<std::pair<AzimuthSpan, double>> shrunk(const ConvexVerticalPrism& prism, const ConvexSpan& span,
                                                       double min_boundary, double max_vertex, double unclipped) const {
    if (!(narrow(min_boundary) - widen(eps) > widen(unclipped))) return std::nullopt;
    const double shift = azimuth_shift(eps, narrow(min_boundary));
    const AzimuthSpan s{span.span.begin + shift, span.span.end - shift};
    if (!(s.end > s.begin) || !(span.span.end - span.span.begin + 2 * shift < kPi - 1e-6)) return std::nullopt;
    const double rise = prism.height - (a.z + zeta);
    const double slope = rise >= 0.0 ? rise / widen(max_vertex + eps) : rise / (narrow(min_boundary) - widen(eps));
    return std::pair{s, narrow(slope)};
  }
};

double yaw_difference(double a, double b) { return std::abs(std::remainder(a - b, kTwoPi)); }

}  // namespace

bool MotionRegion::contains(const Camera& c) const {
  const Camera& a = anchor;
  if (c.hfov != a.hfov || c.vfov != a.vfov || c.near != a.near || c.far != a.far) return false;
  if (length(plan(c.position) - plan(a.position)) > radius || std::abs(c.position.z - a.position.z) > height) return false;
  if (a.omnidirectional()) return true;
  return yaw_difference(c.yaw, a.yaw) + std::abs(c.pitch - a.pitch) + std::abs(c.roll - a.roll) <= turn;
}

HiddenCertificate::HiddenCertificate(const Scene& scene, const Quadtree& quadtree)
    : scene_(scene),
      quadtree_(quadtree),
      cell_epoch_(quadtree.cells().size(), 0),
      building_epoch_(scene.buildings.size(), 0) {}

// The certificate sweep mirrors OH(OS)'s (horizon_sweep.hpp) from the anchor, with every bound
// taken over the region:
//  - an item is marked when its widened span and raised slope lie below the shrunk horizon, so
//    at any camera of the region OH(OS)'s own test (span inside the widened one, slope below the
//    raised one, horizon above the shrunk one on every bin) culls it;
//  - a shadow enters the shrunk horizon only after the sweep (by anchor distance) has passed its
//    CVP's farthest point + 2ε: from any eye of the region the CVP's farthest point is then
//    nearer than the item's nearest point, so OH(OS) has merged that shadow before testing it;
//  - shadows come from every unmarked building whose box certainly meets the view volume of the
//    whole region, visible or not: OH(OS) tests that building at any camera of the region, and
//    either merges its shadows or finds it hidden, in which case its shadows lie below a horizon
//    that is already there.
// Items outside the anchor's volume are neither marked nor used: the per-frame sweep tests them.
void HiddenCertificate::certify(const MotionRegion& region, OcclusionHorizon& horizon, CullStatistics& stats) {
  ++epoch_;
  cells_hidden_ = buildings_hidden_ = 0;
  const Camera& camera = region.anchor;
  const ViewVolume volume(camera);
  const RegionBounds bounds{camera.position, plan(camera.position), region.radius, region.height};
  const double reach = std::hypot(region.radius, region.height);
  const double unclipped = unclipped_distance(camera);
  const Vec2 e = bounds.a2;
  horizon.reset();
  horizon.take_node_visits();

  std::priority_queue<SweepItem, std::vector<SweepItem>, std::greater<SweepItem>> sweep;
  ShadowQueue pending;
  const auto& cells = quadtree_.cells();
  const auto& order = quadtree_.buildings();
  if (!cells.empty() && cells[0].last > cells[0].first) sweep.push({min_distance(e, cells[0].bounds), false, 0});

  auto certified_box = [&](const Box2& box, double top) {
    const auto span = box_span(box, e);
    if (!span) return false;
    const auto g = bounds.grown(span->span, top, min_distance(e, box), max_distance(e, box));
    return g && horizon.hides(g->first, g->second);
  };
  std::vector<std::optional<ConvexSpan>> spans;

  while (!sweep.empty()) {
    const SweepItem item = sweep.top();
    sweep.pop();
    pending.merge_nearer_than(item.distance, horizon, stats);
    if (!item.is_building) {
      const Quadtree::Cell& cell = cells[item.index];
      ++stats.cells_tested;
      const Box3 box{{cell.bounds.lo.x, cell.bounds.lo.y, 0.0}, {cell.bounds.hi.x, cell.bounds.hi.y, cell.max_height}};
      if (!volume.may_intersect(box)) continue;
      if (certified_box(cell.bounds, cell.max_height)) {
        cell_epoch_[item.index] = epoch_;
        ++cells_hidden_;
        continue;
      }
      if (cell.leaf()) {
        for (std::uint32_t i = cell.first; i < cell.last; ++i)
          sweep.push({min_distance(e, scene_.buildings[order[i]].bounds.plan()), true, order[i]});
      } else {
        for (std::uint32_t c = cell.first_child; c < cell.first_child + 4; ++c)
          if (cells[c].last > cells[c].first) sweep.push({min_distance(e, cells[c].bounds), false, c});
      }
      continue;
    }
    const Building& building = scene_.buildings[item.index];
    ++stats.buildings_tested;
    if (!volume.may_intersect(building.bounds)) continue;
    spans.clear();
    bool hidden = certified_box(building.bounds.plan(), building.height);
    if (!hidden) {
      hidden = true;
      for (const ConvexVerticalPrism& prism : building.prisms) {
        spans.push_back(convex_span(prism.ring, e));
        const auto& span = spans.back();
        const auto g = span ? bounds.grown(span->span, prism.height, min_boundary_distance(prism.ring, e),
                                           max_vertex_distance(prism.ring, e))
                            : std::nullopt;
        hidden = hidden && g && horizon.hides(g->first, g->second);
      }
    }
    if (hidden) {
      building_epoch_[item.index] = epoch_;
      ++buildings_hidden_;
      continue;
    }
    if (!certainly_meets(volume, building.bounds, reach, region.turn)) continue;
    for (std::size_t p = 0; p < building.prisms.size(); ++p) {
      const ConvexVerticalPrism& prism = building.prisms[p];
      if (!spans[p]) continue;
      const double near = min_boundary_distance(prism.ring, e), far = max_vertex_distance(prism.ring, e);
      const auto s = bounds.shrunk(prism, *spans[p], near, far, unclipped);
      if (s) pending.push(widen(far + 2 * region.radius), s->first, s->second);
    }
  }
  stats.horizon_nodes += horizon.take_node_visits();
}

}  // namespace cullcheck
