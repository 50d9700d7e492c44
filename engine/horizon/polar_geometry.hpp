// Plan-view angular geometry around the eye: azimuth spans, distances and the elevation
// bounds (as slopes) that the occlusion horizon compares. Double precision; a span computed
// from coordinates carries the rounding bound of its ends (angular_slack: the coordinates'
// magnitude times ε over the tangent vertices' distance), which the horizon adds when it
// rounds the span to bins.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include "core/geometry.hpp"
#include "engine/horizon/occlusion_horizon.hpp"

namespace cullcheck {

// The azimuth span of a convex CCW polygon seen from `eye`, with the indices of the two
// tangent (extreme-azimuth) vertices. Empty when the eye is inside or on the polygon, or so
// close that the span reaches half a turn: such a polygon can neither be culled nor occlude.
struct ConvexSpan {
  AzimuthSpan span;
  std::size_t first_tangent = 0;  // vertex at span.begin
  std::size_t last_tangent = 0;   // vertex at span.end
  // Plan distances from the eye to the tangent vertices (length(ring[tangent] - eye)); 0 for a
  // span of directions.
  double first_distance = 0.0, last_distance = 0.0;
};
std::optional<ConvexSpan> convex_span(const std::vector<Vec2>& ring, Vec2 eye);
// The slack of the span between tangent vertices `lo` and `hi` seen from `eye`, at the given
// distances (length(lo - eye), length(hi - eye)): what convex_span gives its span.
double tangent_slack(Vec2 lo, Vec2 hi, Vec2 eye, double lo_distance, double hi_distance);
std::optional<ConvexSpan> convex_span(const Vec2* ring, std::size_t n, Vec2 eye);
std::optional<ConvexSpan> box_span(const Box2& box, Vec2 eye);
// A box's corners counter-clockwise from its low corner: the ring box_span takes.
inline std::array<Vec2, 4> box_corners(const Box2& box) {
  return {box.lo, Vec2{box.hi.x, box.lo.y}, box.hi, Vec2{box.lo.x, box.hi.y}};
}

// The vertices convex_span (its two tangents) and max_vertex_distance (the farthest) pick, and
// the edges among which min_boundary_distance finds the nearest, for every eye within `radius`
// of `centre`, where that is provably the same for all of them, with a margin far above
// rounding; kNoVertex where it is not (an eye near the ring, tangents or farthest vertices that
// change within the disc, collinear vertices). Meant for a region of eyes queried many times
// (the guarded ΔH's motion region): from an eye of the disc, span_from_tangents,
// distance_to_vertex and distance_to_edge give convex_span's, max_vertex_distance's and
// min_boundary_distance's results bit for bit, reading two vertices, one, and a few edges
// instead of the whole ring.
inline constexpr std::uint32_t kNoVertex = 0xFFFFFFFFu;
struct DiscVertices {
  std::uint32_t first_tangent = kNoVertex, last_tangent = kNoVertex, farthest = kNoVertex;
  // Edges near_first, near_first + 1, ... (near_count of them, cyclically; edge i runs from
  // vertex i - 1 to vertex i): every other edge is farther from every eye of the disc.
  std::uint32_t near_first = kNoVertex, near_count = 0;
  bool tangents_fixed() const { return first_tangent != kNoVertex; }
  bool farthest_fixed() const { return farthest != kNoVertex; }
  bool nearest_fixed() const { return near_first != kNoVertex; }
};
DiscVertices disc_vertices(const Vec2* ring, std::size_t n, Vec2 centre, double radius);
// From an eye of v's disc: convex_span, max_vertex_distance and min_boundary_distance, read off
// the choices v fixed, or computed over the whole ring where it fixed none.
std::optional<ConvexSpan> span_from_tangents(const Vec2* ring, std::size_t n, const DiscVertices& v, Vec2 eye);
double distance_to_vertex(const Vec2* ring, std::size_t n, const DiscVertices& v, Vec2 eye);
double distance_to_edge(const Vec2* ring, std::size_t n, const DiscVertices& v, Vec2 eye);

double max_vertex_distance(const std::vector<Vec2>& ring, Vec2 eye);
double max_vertex_distance(const Vec2* ring, std::size_t n, Vec2 eye);
// Distance from the eye to the polygon's boundary (eye outside).
double min_boundary_distance(const std::vector<Vec2>& ring, Vec2 eye);
double min_boundary_distance(const Vec2* ring, std::size_t n, Vec2 eye);
// Distance from the eye to the far chain: the edges facing away from the eye, through which a
// line of sight leaves the prism.
double min_far_chain_distance(const std::vector<Vec2>& ring, Vec2 eye);

// Highest slope of any point of a solid that stands on the ground, reaches `top`, and lies at
// horizontal distances in [near, far] from an eye at height `eye_z`.
inline double max_slope(double top, double eye_z, double near, double far) {
  return top >= eye_z ? (top - eye_z) / near : (top - eye_z) / far;
}

}  // namespace cullcheck

namespace cullcheck {
struct Camera;
// The azimuths of every direction inside a camera's view volume (6-DoF mapping, ch. 3.1.2):
// the full circle for 360-degree cameras and when the pyramid contains straight up or down;
// otherwise the span of the four edge directions projected to the ground plane (under half a
// turn, since a convex cone that misses the vertical projects to a convex cone).
AzimuthSpan azimuth_coverage(const Camera& camera);
}  // namespace cullcheck
