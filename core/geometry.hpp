// Small value types for the plan view (x, y) and 3D space (x, y, z up), in metres, double
// precision. Angles follow the design's conventions: azimuth from +x counter-clockwise in
// [0, 2*pi), elevation from the horizontal plane in [-pi/2, pi/2].
#pragma once

#include <algorithm>
#include <cmath>
#include <numbers>

namespace cullcheck {

inline constexpr double kPi = std::numbers::pi;
inline constexpr double kTwoPi = 2.0 * std::numbers::pi;

struct Vec2 {
  double x = 0.0;
  double y = 0.0;
  friend constexpr Vec2 operator+(Vec2 a, Vec2 b) { return {a.x + b.x, a.y + b.y}; }
  friend constexpr Vec2 operator-(Vec2 a, Vec2 b) { return {a.x - b.x, a.y - b.y}; }
  friend constexpr Vec2 operator*(Vec2 a, double s) { return {a.x * s, a.y * s}; }
  friend constexpr bool operator==(Vec2, Vec2) = default;
};

struct Vec3 {
  double x = 0.0;
  double y = 0.0;
  double z = 0.0;
  friend constexpr Vec3 operator+(Vec3 a, Vec3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
  friend constexpr Vec3 operator-(Vec3 a, Vec3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
  friend constexpr Vec3 operator*(Vec3 a, double s) { return {a.x * s, a.y * s, a.z * s}; }
  friend constexpr bool operator==(Vec3, Vec3) = default;
};

constexpr double dot(Vec2 a, Vec2 b) { return a.x * b.x + a.y * b.y; }
constexpr double cross(Vec2 a, Vec2 b) { return a.x * b.y - a.y * b.x; }
constexpr double dot(Vec3 a, Vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
constexpr Vec3 cross(Vec3 a, Vec3 b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
// sqrt is correctly rounded everywhere (hypot's accuracy and speed vary by maths library), and
// squares overflow only beyond 1e154 m.
inline double length(Vec2 a) { return std::sqrt(a.x * a.x + a.y * a.y); }
inline double length(Vec3 a) { return std::sqrt(dot(a, a)); }
inline Vec3 normalized(Vec3 a) { return a * (1.0 / length(a)); }
constexpr Vec2 plan(Vec3 a) { return {a.x, a.y}; }

// Plan distance from p to the segment a-b (a point when a == b).
inline double distance_to_segment(Vec2 p, Vec2 a, Vec2 b) {
  const Vec2 ab = b - a;
  const double len2 = dot(ab, ab);
  const double t = len2 > 0.0 ? std::clamp(dot(p - a, ab) / len2, 0.0, 1.0) : 0.0;
  return length(p - (a + ab * t));
}

// Azimuth of a plan-view direction, in [0, 2*pi).
inline double azimuth_of(Vec2 d) {
  double a = std::atan2(d.y, d.x);
  if (a < 0.0) a += kTwoPi;
  return a >= kTwoPi ? 0.0 : a;
}

struct Box2 {
  Vec2 lo{+HUGE_VAL, +HUGE_VAL};
  Vec2 hi{-HUGE_VAL, -HUGE_VAL};
  void extend(Vec2 p) {
    lo = {std::min(lo.x, p.x), std::min(lo.y, p.y)};
    hi = {std::max(hi.x, p.x), std::max(hi.y, p.y)};
  }
  void extend(const Box2& b) {
    if (!b.empty()) extend(b.lo), extend(b.hi);  // an empty box's corners are +-inf
  }
  bool empty() const { return lo.x > hi.x || lo.y > hi.y; }
  Vec2 center() const { return (lo + hi) * 0.5; }
  bool contains(Vec2 p) const { return p.x >= lo.x && p.x <= hi.x && p.y >= lo.y && p.y <= hi.y; }
};

struct Box3 {
  Vec3 lo{+HUGE_VAL, +HUGE_VAL, +HUGE_VAL};
  Vec3 hi{-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
  void extend(Vec3 p) {
    lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
    hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
  }
  Box2 plan() const { return {{lo.x, lo.y}, {hi.x, hi.y}}; }
};

// Horizontal (plan-view) distance range from p to a box: the nearest and farthest points.
inline double min_distance(Vec2 p, const Box2& b) {
  const double dx = std::max({b.lo.x - p.x, 0.0, p.x - b.hi.x});
  const double dy = std::max({b.lo.y - p.y, 0.0, p.y - b.hi.y});
  return std::sqrt(dx * dx + dy * dy);
}
inline double max_distance(Vec2 p, const Box2& b) {
  const double dx = std::max(std::abs(p.x - b.lo.x), std::abs(p.x - b.hi.x));
  const double dy = std::max(std::abs(p.y - b.lo.y), std::abs(p.y - b.hi.y));
  return std::sqrt(dx * dx + dy * dy);
}

}  // namespace cullcheck
