#include "engine/radar/radar_echo.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

#include "engine/horizon/polar_geometry.hpp"
#include "engine/radar/echo_geometry.hpp"
#include "engine/method.hpp"

namespace cullcheck::radar {
namespace {

// A lower bound of the slope of every point of the triangle's far chain (the edges a line of
// sight leaves it through), seen from outside its plan: the chain's lowest vertex at the chain's
// nearest distance when below the eye, at the farthest vertex distance when above.
// A shrunk occluder's chain (ShrunkOccluders) stands at max(floor, its lowest vertex - drop).
double far_chain_min_slope(const std::array<Vec3, 3>& p, const Vec2 (&ring)[3], Vec3 eye, double farthest,
                           double floor = -HUGE_VAL, double drop = 0.0) {
  const Vec2 e = plan(eye);
  double low = HUGE_VAL, d2 = HUGE_VAL;
  for (int k = 0; k < 3; ++k) {
    const Vec2 a = ring[k], b = ring[(k + 1) % 3];
    if (cross(b - a, e - a) < 0.0) continue;  // faces the eye: the near chain
    low = std::min({low, p[k].z, p[(k + 1) % 3].z});
    const Vec2 ab = b - a;
    // A zero-length edge (a wall's plan is a segment) is its end point.
    const double f = dot(ab, ab) > 0.0 ? std::clamp(dot(e - a, ab) / dot(ab, ab), 0.0, 1.0) : 0.0;
    const Vec2 foot = a + ab * f - e;
    d2 = std::min(d2, dot(foot, foot));
  }
  return min_slope(std::max(floor, low - drop), eye.z, std::sqrt(d2), farthest);
}

double slope_to(Vec3 p, Vec3 eye) { return (p.z - eye.z) / length(plan(p) - plan(eye)); }

}  // namespace

AzimuthSpan sector_span(const Sector& s) {
  if (!(s.width < kTwoPi)) return full_circle_span();
  double begin = std::fmod(s.centre - 0.5 * s.width, kTwoPi);
  if (begin < 0) begin += kTwoPi;
  return {begin, begin + s.width};
}

RadarEcho::RadarEcho(const TriangleGrid& grid, RadarRule rule, std::uint32_t horizon_bins)
    : RadarEcho(grid, RadarRules::of(rule), horizon_bins) {}

RadarRules RadarRules::of(RadarRule rule) {
  if (rule == RadarRule::conservative) return {};
  return {CellBound::nearest_point, TriangleTest::vertices, ShadowBound::beta_min, ShadowMerge::immediate};
}

const std::vector<NamedRules>& named_rules() {
  static const std::vector<NamedRules> all = [] {
    const RadarRules c = RadarRules::of(RadarRule::conservative);
    RadarRules cell = c, vertex = c, beta = c, merge = c;
    cell.cell = CellBound::nearest_point;
    vertex.triangle = TriangleTest::vertices;
    beta.shadow = ShadowBound::beta_min;
    merge.merge = ShadowMerge::immediate;
    return std::vector<NamedRules>{{"thesis", RadarRules::of(RadarRule::thesis)},
                                   {"conservative", c},
                                   {"thesis-cell-bound", cell},
                                   {"thesis-vertex-test", vertex},
                                   {"thesis-beta-min", beta},
                                   {"thesis-immediate-merge", merge}};
  }();
  return all;
}

std::optional<RadarRules> rules_named(std::string_view name) {
  for (const NamedRules& n : named_rules())
    if (n.name == name) return n.rules;
  return std::nullopt;
}

RadarEcho::RadarEcho(const TriangleGrid& grid, const RadarRules& rules, std::uint32_t horizon_bins)
    : grid_(grid),
      rules_(rules),
      horizon_(horizon_bins),
      front_(grid),
      seen_(grid.surface().triangle_count(), 0),
      holes_(grid.surface().terrain_has_holes()) {}

bool RadarEcho::faces(std::uint32_t t, Vec3 eye, const ShrunkOccluders* shrunk) const {
  const auto p = grid_.surface().triangle(t);
  const Vec3 n = cross(p[1] - p[0], p[2] - p[0]);
  if (shrunk) {  // facing some eye of the cylinder: the largest n · (E - p0) over it
    const double side = n.x * (eye.x - p[0].x) + n.y * (eye.y - p[0].y) + shrunk->radius * std::hypot(n.x, n.y) +
                        n.z * ((n.z > 0.0 ? eye.z : shrunk->z_low) - p[0].z);
    return side >= 0.0;
  }
  const double side = dot(n, eye - p[0]);
  // Edge-on counts as facing for the conservative rule (a grazing line may touch it).
  return rules_.triangle == TriangleTest::vertices ? side > 0.0 : side >= 0.0;
}

Echo RadarEcho::compute(Vec3 eye, const Sector& sector) { return sweep(eye, sector, nullptr); }

Echo RadarEcho::compute_shrunk(Vec3 eye, const Sector& sector, const ShrunkOccluders& shrunk) {
  if (!(rules_ == RadarRules::of(RadarRule::conservative)))
    throw std::invalid_argument("RadarEcho: shrunk occluders need the conservative rule");
  if (!shrunk.floors || shrunk.floors->size() != seen_.size() || !shrunk.drops || shrunk.drops->size() != seen_.size() ||
      !(shrunk.radius >= 0.0) || !std::isfinite(shrunk.radius) ||
      !(shrunk.z_low <= eye.z))
    throw std::invalid_argument("RadarEcho: shrunk occluders need a floor per triangle, a finite radius and z_low <= the eye's height");
  return sweep(eye, sector, &shrunk);
}

Echo RadarEcho::sweep(Vec3 eye, const Sector& sector, const ShrunkOccluders* shrunk) {
  const Vec2 e = plan(eye);
  if (!grid_.plan().contains(e) || !std::isfinite(eye.z))
    throw std::invalid_argument("RadarEcho: the transmitter must stand over the terrain");
  if (++query_ == 0) {  // the stamps wrapped: start them over
    std::fill(seen_.begin(), seen_.end(), 0);
    query_ = 1;
  }
  const bool immediate = rules_.merge == ShadowMerge::immediate;
  const bool c2 = rules_.cell == CellBound::nearest_point;
  // Shadows prove nothing where a line of sight can pass under the surface through a hole; the
  // thesis's rule uses them anyway (it assumes a whole terrain).
  const bool shadows = !holes_ || rules_.shadow == ShadowBound::beta_min;
  Echo out;
  CullStatistics merged;
  horizon_.reset();
  queue_.clear();
  const AzimuthSpan wanted = sector_span(sector);
  // From a region, the sector is the eyes' own: a thing at distance d from the centre is seen
  // from them up to asin(radius / d) off its azimuth from the centre, and the horizon, which
  // holds what the centre cannot see, is not restricted (that would hide what they see).
  const double radius = shrunk ? shrunk->radius : 0.0;
  if (!wanted.full_circle() && !shrunk) horizon_.restrict_to(wanted);
  const auto meets_sector = [&](const AzimuthSpan& span, double d) {
    return d <= radius ? true : spans_meet(widened(span, azimuth_drift(radius, d)), wanted);
  };

  const std::uint32_t start = grid_.cell_index_at(e);
  front_.start(e);
  const auto in_sector = [&](const GridCell& c) {
    if (wanted.full_circle()) return true;
    const auto span = box_span(c.box, e);
    return !span || meets_sector(span->span, min_distance(e, c.box));
  };

  while (!front_.empty()) {
    const auto [near, index] = front_.next(in_sector);
    const GridCell& cell = grid_.cells()[index];
    if (cell.count == 0) continue;

    if (!immediate) queue_.merge_nearer_than(near, horizon_, merged);
    const double far = max_distance(e, cell.box);
    const auto cell_span = box_span(cell.box, e);
    // Step 1 (the transmitter's cell) and cells the transmitter touches cannot be culled.
    const double cell_slope = c2 ? (cell.top - eye.z) / near : max_slope(cell.top, eye.z, near, far);
    ++out.stats.cells_tested;
    if (index != start && cell_span && horizon_.hides(cell_span->span, cell_slope)) continue;
    ++out.stats.cells_visible;
    const double floor = index != start && cell_span ? horizon_.min_over(cell_span->span) : -HUGE_VAL;

    for (const std::uint32_t t : grid_.triangles_of(cell)) {
      const double top = grid_.top(t);
      // Highest first: once a triangle's top cannot clear H over the cell, no later one can.
      if ((c2 ? (top - eye.z) / near : max_slope(top, eye.z, near, far)) < floor) break;
      if (seen_[t] == query_ || !faces(t, eye, shrunk)) continue;
      ++out.stats.triangles_tested;
      const auto p = grid_.surface().triangle(t);
      const Vec2 ring[3] = {plan(p[0]), plan(p[1]), plan(p[2])};
      const auto span = convex_span(ring, 3, e);
      if (span && !wanted.full_circle() && !meets_sector(span->span, min_boundary_distance(ring, 3, e))) continue;  // outside the sector
      bool visible = index == start;  // step 1: every facing triangle of the transmitter's cell
      if (!visible) {
        if (rules_.triangle == TriangleTest::vertices) {
          const double highest = std::max({slope_to(p[0], eye), slope_to(p[1], eye), slope_to(p[2], eye)});
          visible = !span || !horizon_.hides(span->span, highest);
        } else {
          // The triangle's part in this cell lies in the cell's box clipped to its plan box.
          Box2 box;
          for (const Vec2& v : ring) box.extend(v);
          const Box2 part = intersection(box, cell.box);
          const auto part_span = box_span(part, e);
          visible = !part_span ||
                    !horizon_.hides(part_span->span, max_slope(top, eye.z, min_distance(e, part), max_distance(e, part)));
        }
      }
      if (!visible) continue;
      seen_[t] = query_;
      out.visible.push_back(t);
      if (!span || !shadows) continue;
      const double farthest = std::max({length(ring[0] - e), length(ring[1] - e), length(ring[2] - e)});
      // β_min: the lower elevation of the two extreme-azimuth vertices (Fig. 3.12-3.13).
      // A building's wall (its plan a segment) stands on a solid rectangle from the buried base
      // to its top vertex's height all along the segment: a line crossing the segment below
      // that top is blocked by the wall or the ground, so the bound is the top over the segment.
      const bool wall = grid_.surface().building_of(t) >= 0 && cross(ring[1] - ring[0], ring[2] - ring[0]) == 0.0;
      // A shrunk occluder's far chain stands at its floor (walls included: their solid is shrunk away).
      const double slope = rules_.shadow == ShadowBound::beta_min
                               ? std::min(slope_to(p[span->first_tangent], eye), slope_to(p[span->last_tangent], eye))
                           : shrunk ? far_chain_min_slope(p, ring, eye, farthest, (*shrunk->floors)[t], (*shrunk->drops)[t])
                           : wall   ? min_slope(top, eye.z, min_boundary_distance(ring, 3, e), farthest)
                                    : far_chain_min_slope(p, ring, eye, farthest);
      if (immediate) {
        horizon_.raise(span->span, slope);
        ++merged.occluders_applied;
      } else {
        queue_.push(farthest, span->span, slope);
      }
    }
  }
  out.stats.shadows = merged.occluders_applied;
  std::sort(out.visible.begin(), out.visible.end());
  return out;
}

}  // namespace cullcheck::radar
