// Plan-view helpers the radar echoes share (engine/radar/radar_echo.cpp, region_echo.cpp):
// sectors as azimuth spans, spans widened or shrunk by an angle, and the slope bounds of a
// triangle's lowest point.
#pragma once

#include <algorithm>
#include <cmath>
#include <optional>

#include "core/geometry.hpp"
#include "engine/horizon/occlusion_horizon.hpp"

namespace cullcheck::radar {

struct Sector;

// Lowest slope of any point of a triangle whose lowest vertex is `bottom`, at plan distances in
// [near, far] from an eye at height eye_z (the mirror of max_slope).
inline double min_slope(double bottom, double eye_z, double near, double far) {
  return bottom <= eye_z ? (bottom - eye_z) / near : (bottom - eye_z) / far;
}

inline AzimuthSpan full_circle_span() { return {0.0, kTwoPi}; }

// Whether two azimuth spans share a direction (with a little slack, so a boundary cell is kept).
inline bool spans_meet(const AzimuthSpan& a, const AzimuthSpan& b) {
  if (a.full_circle() || b.full_circle()) return true;
  constexpr double slack = 1e-9;
  for (int k = -1; k <= 1; ++k)
    if (a.begin <= b.end + k * kTwoPi + slack && b.begin + k * kTwoPi <= a.end + slack) return true;
  return false;
}

// The span grown by `by` radians at both ends (the full circle once it covers a turn).
inline AzimuthSpan widened(AzimuthSpan s, double by) {
  if (s.full_circle()) return s;
  if (s.end - s.begin + 2.0 * by >= kTwoPi) return {0.0, kTwoPi, s.slack};
  s.begin -= by, s.end += by;
  if (s.begin < 0.0) s.begin += kTwoPi, s.end += kTwoPi;
  return s;
}

// The span less `by` radians at both ends; none when nothing is left.
inline std::optional<AzimuthSpan> shrunk(AzimuthSpan s, double by) {
  if (s.full_circle()) return std::nullopt;  // a full-circle shadow comes from no triangle
  s.begin += by, s.end -= by;
  if (!(s.begin < s.end)) return std::nullopt;
  if (s.begin >= kTwoPi) s.begin -= kTwoPi, s.end -= kTwoPi;
  return s;
}

// How far the azimuth of a point at plan distance d from a centre can turn when the eye moves
// anywhere within `radius` of the centre (d > radius): asin(radius / d), rounded up.
inline double azimuth_drift(double radius, double d) {
  if (radius <= 0.0) return 0.0;
  return std::asin(std::min(1.0, radius / d)) * (1.0 + 1e-9) + 1e-12;
}

inline Box2 intersection(const Box2& a, const Box2& b) {
  return {{std::max(a.lo.x, b.lo.x), std::max(a.lo.y, b.lo.y)}, {std::min(a.hi.x, b.hi.x), std::min(a.hi.y, b.hi.y)}};
}

}  // namespace cullcheck::radar
