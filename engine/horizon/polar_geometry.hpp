// Plan-view angular geometry around the eye: azimuth spans, distances and the elevation
// bounds (as slopes) that the occlusion horizon compares. Double precision; a span computed
// from coordinates carries the rounding bound of its ends (angular_slack: the coordinates'
// magnitude times ε over the tangent vertices' distance), which the horizon adds when it
// rounds the span to bins.
#pragma once

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
};
std::optional<ConvexSpan> convex_span(const std::vector<Vec2>& ring, Vec2 eye);
std::optional<ConvexSpan> convex_span(const Vec2* ring, std::size_t n, Vec2 eye);
std::optional<ConvexSpan> box_span(const Box2& box, Vec2 eye);

double max_vertex_distance(const std::vector<Vec2>& ring, Vec2 eye);
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
