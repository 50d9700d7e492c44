#include "engine/horizon/polar_geometry.hpp"

#include <algorithm>
#include <cmath>

#include "core/camera.hpp"
#include "engine/horizon/fast_angle.hpp"

namespace cullcheck {
namespace {

// Spans this close to half a turn come from an eye practically on the polygon.
constexpr double kMaxSpan = kPi - 1e-9;

}  // namespace

namespace {

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
  const double width = fast_atan2(cross(dlo, dhi), dot(dlo, dhi));
  if (!(width >= 0.0) || width >= kMaxSpan) return std::nullopt;
  // Cross products order directions only within half a turn: an eye on (or within rounding of)
  // an edge sees two vertices in opposite directions, and the sign between them is noise, so the
  // extremes found may leave a vertex out. Within a true span below half a turn every direction
  // is less than a quarter turn from the bisector of the extremes; one that is not betrays it.
  const double llo = length(dlo), lhi = length(dhi);
  const Vec2 bisector = dlo * (1.0 / llo) + dhi * (1.0 / lhi);
  for (std::size_t i = 0; i < n; ++i)
    if (!(dot(ring[i] - eye, bisector) > 0.0)) return std::nullopt;
  const double begin = fast_azimuth(dlo);
  // Both ends are azimuths of tangent vertices: their rounding grows with the coordinates'
  // magnitude and shrinks with the vertices' distance (angular_slack).
  const double magnitude = std::max({std::abs(eye.x), std::abs(eye.y), std::abs(ring[lo].x), std::abs(ring[lo].y),
                                     std::abs(ring[hi].x), std::abs(ring[hi].y)});
  const double slack = angular_slack(magnitude, std::min(llo, lhi));
  return ConvexSpan{{begin, begin + width, slack}, lo, hi};
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

std::optional<ConvexSpan> convex_span(const std::vector<Vec2>& ring, Vec2 eye) {
  return span_of_convex(ring.data(), ring.size(), eye);
}

std::optional<ConvexSpan> convex_span(const Vec2* ring, std::size_t n, Vec2 eye) { return span_of_convex(ring, n, eye); }

std::optional<ConvexSpan> box_span(const Box2& box, Vec2 eye) {
  const Vec2 corners[4] = {box.lo, {box.hi.x, box.lo.y}, box.hi, {box.lo.x, box.hi.y}};
  return span_of_convex(corners, 4, eye);
}

double max_vertex_distance(const std::vector<Vec2>& ring, Vec2 eye) {
  double d2 = 0.0;
  for (Vec2 p : ring) d2 = std::max(d2, dot(p - eye, p - eye));
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
