#include "engine/horizon/polar_geometry.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "core/camera.hpp"
#include "engine/horizon/fast_angle.hpp"

namespace cullcheck {
namespace {

// Spans this close to half a turn come from an eye practically on the polygon.
constexpr double kMaxSpan = kPi - 1e-9;

// The span between the tangent vertices lo and hi (dlo = ring[lo] - eye, dhi = ring[hi] - eye)
// as span_of_convex finishes it. `check_bisector` is off only where the caller has proven that
// the check passes (span_from_tangents over a disc_vertices disc).
std::optional<ConvexSpan> span_between(const Vec2* ring, std::size_t n, std::size_t lo, std::size_t hi, Vec2 eye,
                                       Vec2 dlo, Vec2 dhi, bool check_bisector) {
  const double width = fast_atan2(cross(dlo, dhi), dot(dlo, dhi));
  if (!(width >= 0.0) || width >= kMaxSpan) return std::nullopt;
  // Cross products order directions only within half a turn: an eye on (or within rounding of)
  // an edge sees two vertices in opposite directions, and the sign between them is noise, so the
  // extremes found may leave a vertex out. Within a true span below half a turn every direction
  // is less than a quarter turn from the bisector of the extremes; one that is not betrays it.
  const double llo = length(dlo), lhi = length(dhi);
  if (check_bisector) {
    const Vec2 bisector = dlo * (1.0 / llo) + dhi * (1.0 / lhi);
    for (std::size_t i = 0; i < n; ++i)
      if (!(dot(ring[i] - eye, bisector) > 0.0)) return std::nullopt;
  }
  const double begin = fast_azimuth(dlo);
  return ConvexSpan{{begin, begin + width, tangent_slack(ring[lo], ring[hi], eye, llo, lhi)}, lo, hi, llo, lhi};
}

// The span of a convex polygon's vertices seen from an eye outside it. Every direction then
// lies within less than half a turn, where the sign of a cross product orders directions by
// angle, so the two extreme (tangent) vertices are found without trigonometry and atan2 is
// called twice (fast_atan2: within 1e-15 rad, far inside the span's slack). Empty when the eye
// is inside or on the polygon, or so close that the span (nearly) reaches half a turn.
std::optional<ConvexSpan> span_of_convex(const Vec2* ring, std::size_t n, Vec2 eye) {
  // One pass finds whether the eye is outside (behind some edge of the counter-clockwise ring)
  // and the extreme directions; the extremes only count once the eye is known to be outside.
  bool outside = false;
  std::size_t lo = 0, hi = 0;
  Vec2 dlo = ring[0] - eye, dhi = dlo;
  if (dlo.x == 0.0 && dlo.y == 0.0) return std::nullopt;
  outside = cross(ring[0] - ring[n - 1], eye - ring[n - 1]) < 0.0;
  for (std::size_t i = 1; i < n; ++i) {
    const Vec2 d = ring[i] - eye;
    if (d.x == 0.0 && d.y == 0.0) return std::nullopt;
    outside = outside || cross(ring[i] - ring[i - 1], eye - ring[i - 1]) < 0.0;
    if (cross(dlo, d) < 0.0) lo = i, dlo = d;
    if (cross(dhi, d) > 0.0) hi = i, dhi = d;
  }
  if (!outside) return std::nullopt;
  return span_between(ring, n, lo, hi, eye, dlo, dhi, /*check_bisector=*/true);
}

// Squared distance from p to the segment ab.
double segment_distance_squared(Vec2 p, Vec2 a, Vec2 b) {
  const Vec2 ab = b - a;
  const double len2 = dot(ab, ab);
  double t = len2 > 0 ? dot(p - a, ab) / len2 : 0.0;
  t = std::clamp(t, 0.0, 1.0);
  const Vec2 d = p - (a + ab * t);
  return dot(d, d);
}

// The smallest azimuth span holding every direction, with the indices of the extreme ones.
// Relative to the first direction's angle, a set spanning less than half a turn has its
// extremes at the smallest and largest deltas in (-π, π]. Empty for a zero direction or a set
// spanning (nearly) half a turn or more.
std::optional<ConvexSpan> span_of_directions(const std::vector<Vec2>& directions, double min_length) {
  if (length(directions[0]) <= min_length) return std::nullopt;
  const double reference = std::atan2(directions[0].y, directions[0].x);
  double lo = 0.0, hi = 0.0;
  std::size_t lo_index = 0, hi_index = 0;
  for (std::size_t i = 1; i < directions.size(); ++i) {
    const Vec2 d = directions[i];
    if (length(d) <= min_length) return std::nullopt;
    const double delta = std::remainder(std::atan2(d.y, d.x) - reference, kTwoPi);
    if (delta < lo) lo = delta, lo_index = i;
    if (delta > hi) hi = delta, hi_index = i;
  }
  if (hi - lo >= kMaxSpan) return std::nullopt;
  double begin = reference + lo;
  begin = begin < 0.0 ? begin + kTwoPi : (begin >= kTwoPi ? begin - kTwoPi : begin);
  return ConvexSpan{{begin, begin + (hi - lo)}, lo_index, hi_index};
}

}  // namespace

double tangent_slack(Vec2 lo, Vec2 hi, Vec2 eye, double lo_distance, double hi_distance) {
  // Both ends are azimuths of tangent vertices: their rounding grows with the coordinates'
  // magnitude and shrinks with the vertices' distance (angular_slack).
  const double magnitude = std::max({std::abs(eye.x), std::abs(eye.y), std::abs(lo.x), std::abs(lo.y), std::abs(hi.x), std::abs(hi.y)});
  return angular_slack(magnitude, std::min(lo_distance, hi_distance));
}

std::optional<ConvexSpan> convex_span(const std::vector<Vec2>& ring, Vec2 eye) {
  return span_of_convex(ring.data(), ring.size(), eye);
}

std::optional<ConvexSpan> convex_span(const Vec2* ring, std::size_t n, Vec2 eye) { return span_of_convex(ring, n, eye); }

std::optional<ConvexSpan> box_span(const Box2& box, Vec2 eye) {
  const std::array<Vec2, 4> corners = box_corners(box);
  return span_of_convex(corners.data(), 4, eye);
}

std::optional<ConvexSpan> span_from_tangents(const Vec2* ring, std::size_t n, const DiscVertices& v, Vec2 eye) {
  if (!v.tangents_fixed()) return span_of_convex(ring, n, eye);
  return span_between(ring, n, v.first_tangent, v.last_tangent, eye, ring[v.first_tangent] - eye,
                      ring[v.last_tangent] - eye, /*check_bisector=*/false);
}

double distance_to_vertex(const Vec2* ring, std::size_t n, const DiscVertices& v, Vec2 eye) {
  if (!v.farthest_fixed()) return max_vertex_distance(ring, n, eye);
  const Vec2 d = ring[v.farthest] - eye;
  return std::sqrt(std::max(0.0, dot(d, d)));  // max_vertex_distance's arithmetic
}

double distance_to_edge(const Vec2* ring, std::size_t n, const DiscVertices& v, Vec2 eye) {
  if (!v.nearest_fixed()) return min_boundary_distance(ring, n, eye);
  // min_boundary_distance's arithmetic over the edges that can be nearest; a minimum of the same
  // values in another order is the same value.
  double d2 = HUGE_VAL;
  for (std::size_t k = 0, i = v.near_first; k < v.near_count; ++k, i = i + 1 == n ? 0 : i + 1)
    d2 = std::min(d2, segment_distance_squared(eye, ring[i == 0 ? n - 1 : i - 1], ring[i]));
  return std::sqrt(d2);
}

// Why each choice holds for every eye e within r of the centre c, computed as the per-eye
// functions compute it (rounding of a cross or dot product of differences is a few 1e-16 of the
// product of their lengths; every margin below is 1e-9 of it):
//  - outside: some edge ab has cross(b - a, e - a) <= cross(b - a, c - a) + r |b - a| < 0 with
//    margin, so span_of_convex finds the eye outside;
//  - tangents: cross(T - e, N - e) = cross(T - e, N - T) is linear in e, so its least value over
//    the disc is cross(T - c, N - T) - r |N - T|. With both neighbours N of the first tangent T
//    counter-clockwise of it by a margin (clockwise for the last), and the disc clear of the
//    ring's box by 1e-3 of its diagonal (every direction then lies within half a turn less
//    1e-3 rad), every other vertex is at least as far round as a neighbour (a convex ring seen
//    from outside turns one way along each chain), so span_of_convex's running extremes end at
//    T whatever order it meets the others in, and its bisector check passes;
//  - farthest: |F - e|^2 - |V - e|^2 >= |F - c|^2 - |V - c|^2 - 2 r |F - V| for every other V;
//  - nearest edges: a distance moves by at most r over the disc, so an edge whose distance from
//    c exceeds the least one's by more than 2r is never the nearest. The margin there also covers
//    the coordinates' magnitude, since a segment's nearest point is rounded in absolute terms.
//    The edges that may be nearest are kept as the shortest cyclic run holding them all.
DiscVertices disc_vertices(const Vec2* ring, std::size_t n, Vec2 centre, double radius) {
  DiscVertices out;
  if (n < 3 || !(radius >= 0.0) || !std::isfinite(radius)) return out;
  Box2 box;
  for (std::size_t i = 0; i < n; ++i) box.extend(ring[i]);
  const double diag = length(box.hi - box.lo);
  const double clearance = min_distance(centre, box) - radius;
  if (!(clearance > 1e-3 * diag) || !std::isfinite(diag)) return out;
  constexpr double kMargin = 1e-9;

  bool outside = false;
  for (std::size_t i = 0, j = n - 1; i < n && !outside; j = i++) {
    const Vec2 edge = ring[i] - ring[j];
    const double le = length(edge);
    outside = cross(edge, centre - ring[j]) + radius * le < -kMargin * le * (length(centre - ring[j]) + radius);
  }
  const auto span = outside ? span_of_convex(ring, n, centre) : std::nullopt;
  auto clear_of_neighbours = [&](std::size_t t, double side) {
    const Vec2 tip = ring[t];
    for (const std::size_t k : {(t + n - 1) % n, (t + 1) % n}) {
      const Vec2 edge = ring[k] - tip;
      const double least = side * cross(tip - centre, edge) - radius * length(edge);
      if (!(least > kMargin * (length(tip - centre) + radius) * (length(ring[k] - centre) + radius))) return false;
    }
    return true;
  };
  if (span && span->first_tangent != span->last_tangent && clear_of_neighbours(span->first_tangent, 1.0) &&
      clear_of_neighbours(span->last_tangent, -1.0)) {
    out.first_tangent = static_cast<std::uint32_t>(span->first_tangent);
    out.last_tangent = static_cast<std::uint32_t>(span->last_tangent);
  }

  std::size_t far = 0;
  double best = -1.0;
  for (std::size_t i = 0; i < n; ++i) {
    const double d2 = dot(ring[i] - centre, ring[i] - centre);
    if (d2 > best) best = d2, far = i;
  }
  const double reach = std::sqrt(best) + radius;
  bool alone = true;
  for (std::size_t i = 0; i < n && alone; ++i)
    alone = i == far || best - dot(ring[i] - centre, ring[i] - centre) - 2.0 * radius * length(ring[far] - ring[i]) >
                            kMargin * reach * reach;
  if (alone) out.farthest = static_cast<std::uint32_t>(far);

  auto edge_distance = [&](std::size_t i) {
    return std::sqrt(segment_distance_squared(centre, ring[i == 0 ? n - 1 : i - 1], ring[i]));
  };
  double nearest = HUGE_VAL;
  for (std::size_t i = 0; i < n; ++i) nearest = std::min(nearest, edge_distance(i));
  const double magnitude = std::max({std::abs(centre.x), std::abs(centre.y), std::abs(box.lo.x), std::abs(box.lo.y),
                                     std::abs(box.hi.x), std::abs(box.hi.y)});
  const double beaten = (nearest + radius) * (1.0 + kMargin) + kMargin * magnitude + radius;
  // The longest cyclic gap between edges that may be nearest; the run is the rest.
  std::size_t candidates = 0, first = 0, gap = 0, last = kNoVertex;
  for (std::size_t k = 0; k < 2 * n; ++k) {
    const std::size_t i = k % n;
    if (!(edge_distance(i) <= beaten)) continue;
    if (k < n) ++candidates;
    if (last != kNoVertex && k - last - 1 > gap && last < n) gap = k - last - 1, first = i;
    last = k;
  }
  if (candidates > 0 && gap > 0 && std::isfinite(nearest)) {
    out.near_first = static_cast<std::uint32_t>(first);
    out.near_count = static_cast<std::uint32_t>(n - gap);
  }
  return out;
}

double max_vertex_distance(const std::vector<Vec2>& ring, Vec2 eye) { return max_vertex_distance(ring.data(), ring.size(), eye); }

double max_vertex_distance(const Vec2* ring, std::size_t n, Vec2 eye) {
  double d2 = 0.0;
  for (std::size_t i = 0; i < n; ++i) d2 = std::max(d2, dot(ring[i] - eye, ring[i] - eye));
  return std::sqrt(d2);
}

double min_boundary_distance(const std::vector<Vec2>& ring, Vec2 eye) { return min_boundary_distance(ring.data(), ring.size(), eye); }

double min_boundary_distance(const Vec2* ring, std::size_t n, Vec2 eye) {
  double d2 = HUGE_VAL;
  for (std::size_t i = 0, j = n - 1; i < n; j = i++) d2 = std::min(d2, segment_distance_squared(eye, ring[j], ring[i]));
  return std::sqrt(d2);
}

double min_far_chain_distance(const std::vector<Vec2>& ring, Vec2 eye) {
  double d2 = HUGE_VAL;
  for (std::size_t i = 0, n = ring.size(), j = n - 1; i < n; j = i++) {
    const Vec2 a = ring[j], b = ring[i];
    // Counter-clockwise ring: the eye on the inner side of an edge's line (or on it) means the
    // edge faces away from the eye.
    if (cross(b - a, eye - a) >= 0.0) d2 = std::min(d2, segment_distance_squared(eye, a, b));
  }
  return std::sqrt(d2);
}


AzimuthSpan azimuth_coverage(const Camera& camera) {
  const AzimuthSpan full{0.0, kTwoPi};
  if (camera.omnidirectional()) return full;
  // A vertical direction inside (or on) the pyramid: the side planes of the view volume.
  const ViewVolume volume(camera);
  for (double vertical : {1.0, -1.0}) {
    bool inside = true;
    for (int i = 0; i < 4; ++i) inside = inside && volume.planes[i].n.z * vertical >= -1e-12;
    if (inside) return full;
  }
  const CameraBasis b = basis_of(camera);
  const double th = std::tan(camera.hfov / 2), tv = std::tan(camera.vfov / 2);
  std::vector<Vec2> corners;
  for (double x : {-th, th})
    for (double y : {-tv, tv}) corners.push_back(plan(b.forward + b.right * x + b.up * y));
  const auto span = span_of_directions(corners, 1e-12);
  return span ? span->span : full;
}

}  // namespace cullcheck
