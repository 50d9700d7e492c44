// Small scenes drawn around one ε-disc, each built to reach one case where a from-region method's
// bookkeeping (not its shrinking) decides the answer. The geometry is written here (plan vectors
// and boxes only), shared with neither the engine nor the oracle. The disc's centre C stands at
// `origin`, looking along +y (yaw π/2) at eye height 1.7 m; each scene is a wide wall A across the
// view and one more building B.
//
//  - shallow_wall: A is shallower than 2ε (its farthest vertex is less than 2ε beyond its
//    nearest point) and B, lower than the eye, stands in front of A's face but farther from C
//    than A's nearest point, inside A's span narrowed by asin(ε / r). The sweep reaches B after
//    A (it is keyed on nearest distance) while B lies wholly in front of A: a method that merges
//    A's shrunk shadow before A's farthest point (ci/mutants: shrink_corrected_merged_2eps_early)
//    culls B, which every eye of the disc sees.
//  - clipped_wall: A's face lies just beyond the centre's unclipped distance (the distance past
//    which nothing is in front of the near plane, horizon_sweep.hpp), by less than ε; B stands
//    behind A, lower than the eye. From the disc's front the whole of A is nearer than the near
//    plane and hides nothing: B is in view there. A method that decides "A may be clipped" from
//    the centre alone uses A as an occluder and culls B.
#pragma once

#include <rapidcheck.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <ostream>
#include <tuple>
#include <vector>

#include "core/camera.hpp"
#include "core/geometry.hpp"
#include "core/scene.hpp"
#include "core/scene_io.hpp"
#include "generators/angles.hpp"
#include "generators/rapidcheck_gens.hpp"

namespace cullcheck::properties {

inline constexpr double kDrawnEye = 1.7;

struct DrawnDisc {
  Scene scene;
  Camera centre;
  double radius = 1.0;
  ObjectId wall = 0, target = 1;
  bool usable = false;  // false: the draw's numbers admit no such scene (the property skips it, tagged)
};

namespace drawn_detail {

// Plan distance from p to an axis-aligned box [lo, hi].
inline double box_distance(Vec2 p, Vec2 lo, Vec2 hi) {
  const double dx = std::max({lo.x - p.x, 0.0, p.x - hi.x}), dy = std::max({lo.y - p.y, 0.0, p.y - hi.y});
  return std::hypot(dx, dy);
}
inline double farthest_corner(Vec2 p, Vec2 lo, Vec2 hi) {
  return std::hypot(std::max(std::abs(lo.x - p.x), std::abs(hi.x - p.x)), std::max(std::abs(lo.y - p.y), std::abs(hi.y - p.y)));
}
inline std::vector<Vec2> corners(Vec2 lo, Vec2 hi) { return {lo, {hi.x, lo.y}, hi, {lo.x, hi.y}}; }

// A box in front of the centre (y > 0): its corners' angles from the +y axis (positive to the
// left, -x), and the distances of the two extreme ones (the tangent vertices).
struct Span {
  double lo, hi, d_lo, d_hi;
};
inline Span span_of(Vec2 lo, Vec2 hi) {
  Span s{HUGE_VAL, -HUGE_VAL, 0, 0};
  for (Vec2 c : corners(lo, hi)) {
    const double a = std::atan2(-c.x, c.y);
    if (a < s.lo) s.lo = a, s.d_lo = length(c);
    if (a > s.hi) s.hi = a, s.d_hi = length(c);
  }
  return s;
}
// Whether every corner of [lo, hi] lies inside `s` narrowed by asin(ε / d) at each end, with a
// margin of `margin` radians.
inline bool inside_narrowed(const Span& s, double eps, Vec2 lo, Vec2 hi, double margin) {
  if (!(s.d_lo > eps && s.d_hi > eps)) return false;
  const double a = s.lo + std::asin(eps / s.d_lo) + margin, b = s.hi - std::asin(eps / s.d_hi) - margin;
  for (Vec2 c : corners(lo, hi)) {
    const double t = std::atan2(-c.x, c.y);
    if (!(t > a && t < b)) return false;
  }
  return true;
}

inline Camera centre_camera(Vec2 origin, double hfov, double near) {
  Camera c;
  c.position = {origin.x, origin.y, kDrawnEye};
  c.yaw = kPi / 2;
  c.hfov = hfov;
  c.vfov = hfov * 0.75;
  c.near = near;
  return c;
}

inline Scene two_boxes(Vec2 origin, Vec2 a_lo, Vec2 a_hi, double a_height, Vec2 b_lo, Vec2 b_hi, double b_height) {
  Scene s;
  s.buildings = {box_building(0, origin.x + a_lo.x, origin.y + a_lo.y, origin.x + a_hi.x, origin.y + a_hi.y, a_height),
                 box_building(1, origin.x + b_lo.x, origin.y + b_lo.y, origin.x + b_hi.x, origin.y + b_hi.y, b_height)};
  return s;
}

}  // namespace drawn_detail

// What the shallow-wall generator draws (each shrinks towards its first choice).
struct ShallowWallDraw {
  double radius = 1.0;   // ε
  double distance = 12;  // r: A's face, metres ahead of C
  double depth = 0.6;    // A's farthest vertex lies depth * 2ε beyond r
  double offset = 0.0;   // A's centre, as a fraction of its half-width, to the side
  double thickness = 0.2;
  double height = 8.0;   // A's height
  double side = 0.4;     // B's side, metres
  double gap = 0.05;     // between B's back and A's face
  double beyond = 0.1;   // B's nearest point beyond A's nearest point, metres (the least it may be)
  double lateral = 0.0;  // B moved further out by this many metres
  bool left = false;     // B on A's left (-x) side
  double target_height = 0.8;
  Vec2 origin{0, 0};
};

inline void showValue(const ShallowWallDraw& d, std::ostream& os) {
  os << "{radius: " << d.radius << ", distance: " << d.distance << ", depth: " << d.depth << ", offset: " << d.offset
     << ", thickness: " << d.thickness << ", height: " << d.height << ", side: " << d.side << ", gap: " << d.gap
     << ", beyond: " << d.beyond << ", lateral: " << d.lateral << ", left: " << d.left << ", target_height: " << d.target_height
     << ", origin: (" << d.origin.x << ", " << d.origin.y << ")}";
}

inline DrawnDisc shallow_wall(const ShallowWallDraw& d) {
  using namespace drawn_detail;
  DrawnDisc out;
  out.radius = d.radius;
  const double eps = d.radius, r = d.distance, t = d.thickness;
  // Half-width from the depth: farthest vertex at r + depth * 2ε.
  const double far = r + d.depth * 2 * eps;
  if (!(far > r + t)) return out;
  const double half = std::sqrt(far * far - (r + t) * (r + t)) / (1.0 + std::abs(d.offset));
  const double xc = d.offset * half;
  const Vec2 a_lo{xc - half, r}, a_hi{xc + half, r + t};
  const Vec2 c{0, 0};
  const double a_near = box_distance(c, a_lo, a_hi), a_far = farthest_corner(c, a_lo, a_hi);
  // B: a square whose back is `gap` in front of A's face, pushed out sideways until its nearest
  // point is `beyond` farther than A's nearest (so the sweep reaches it after A).
  const double y1 = r - d.gap, y0 = y1 - d.side;
  const double want = a_near + d.beyond;
  if (!(y0 > 0.5) || !(want > y0)) return out;
  const double x_near = std::sqrt(want * want - y0 * y0) + d.lateral;
  const double sign = d.left ? -1.0 : 1.0;
  const Vec2 b_lo{sign > 0 ? x_near : -x_near - d.side, y0}, b_hi{sign > 0 ? x_near + d.side : -x_near, y1};
  const double b_near = box_distance(c, b_lo, b_hi);
  if (!(b_near > a_near + 0.05) || !(b_near > a_far - 2 * eps + 0.05)) return out;
  if (!inside_narrowed(span_of(a_lo, a_hi), eps, b_lo, b_hi, 0.01)) return out;
  if (!(a_near > eps + 0.5) || !(d.height > kDrawnEye + 0.5) || !(d.target_height < kDrawnEye - 0.2)) return out;
  out.scene = two_boxes(d.origin, a_lo, a_hi, d.height, b_lo, b_hi, d.target_height);
  out.centre = centre_camera(d.origin, generators::radians(90.0), 0.1);
  out.usable = true;
  return out;
}

inline rc::Gen<Vec2> drawn_origin() {
  // The scene's place in the world (within the range a scene file is not rebased in, so that a
  // replay reads the same coordinates).
  return rc::gen::element(Vec2{0, 0}, Vec2{137.25, -42.5}, Vec2{5000.5, -2500.25});
}

inline rc::Gen<ShallowWallDraw> shallow_wall_draw() {
  return rc::gen::map(
      rc::gen::tuple(rc::gen::element(1.0, 2.0, 3.0, 0.5), rc::gen::element(8.0, 5.0, 12.0, 20.0, 30.0),
                     rc::gen::element(0.8, 0.5, 0.65, 0.95), rc::gen::element(0.0, 0.2, -0.3, 0.5),
                     rc::gen::element(0.2, 0.05, 0.5), rc::gen::element(8.0, 3.0, 20.0), rc::gen::element(0.4, 0.2, 0.8),
                     rc::gen::element(0.05, 0.01, 0.3), rc::gen::element(0.1, 0.03, 0.3), rc::gen::element(0.0, 0.3, 1.0),
                     rc::gen::arbitrary<bool>(), rc::gen::element(0.8, 0.3, 1.4), drawn_origin()),
      [](const auto& tuple) {
        ShallowWallDraw d;
        std::tie(d.radius, d.distance, d.depth, d.offset, d.thickness, d.height, d.side, d.gap, d.beyond, d.lateral, d.left,
                 d.target_height, d.origin) = tuple;
        return d;
      });
}

// What the clipped-wall generator draws.
struct ClippedWallDraw {
  double radius = 1.0;   // ε
  double near = 2.0;     // the cameras' near plane
  double hfov_deg = 60;  // vfov is 3/4 of it
  double past = 0.2;     // A's face lies past * ε beyond the centre's unclipped distance
  double thickness = 0.2;
  double half_width = 20.0;
  double height = 8.0;
  double behind = 6.0;  // B's front, metres behind A's back
  double side = 2.0;
  double target_height = 1.0;
  Vec2 origin{0, 0};
};

inline void showValue(const ClippedWallDraw& d, std::ostream& os) {
  os << "{radius: " << d.radius << ", near: " << d.near << ", hfov_deg: " << d.hfov_deg << ", past: " << d.past
     << ", thickness: " << d.thickness << ", half_width: " << d.half_width << ", height: " << d.height << ", behind: " << d.behind
     << ", side: " << d.side << ", target_height: " << d.target_height << ", origin: (" << d.origin.x << ", " << d.origin.y << ")}";
}

// The unclipped distance of horizon_sweep.hpp, written again: a point of the view volume is at
// least near deep, so at least near / cos(corner angle) = near * sqrt(1 + tan² h/2 + tan² v/2) away.
inline double drawn_unclipped(const Camera& c) {
  return c.near * std::sqrt(1.0 + std::pow(std::tan(c.hfov / 2), 2) + std::pow(std::tan(c.vfov / 2), 2));
}

inline DrawnDisc clipped_wall(const ClippedWallDraw& d) {
  using namespace drawn_detail;
  DrawnDisc out;
  out.radius = d.radius;
  const Camera centre = centre_camera(d.origin, generators::radians(d.hfov_deg), d.near);
  const double eps = d.radius, r = drawn_unclipped(centre) + d.past * eps, t = d.thickness;
  const Vec2 a_lo{-d.half_width, r}, a_hi{d.half_width, r + t};
  // The disc's front eye sees the whole of A nearer than its near plane only when A's back is.
  if (!(r + t - eps < d.near)) return out;
  const Vec2 b_lo{-d.side / 2, r + t + d.behind}, b_hi{d.side / 2, r + t + d.behind + d.side};
  if (!inside_narrowed(span_of(a_lo, a_hi), eps, b_lo, b_hi, 0.01)) return out;
  if (!(d.height > kDrawnEye + 0.5) || !(d.target_height < kDrawnEye - 0.2)) return out;
  out.scene = two_boxes(d.origin, a_lo, a_hi, d.height, b_lo, b_hi, d.target_height);
  out.centre = centre;
  out.usable = true;
  return out;
}

inline rc::Gen<ClippedWallDraw> clipped_wall_draw() {
  return rc::gen::map(rc::gen::tuple(rc::gen::element(1.0, 2.0, 3.0, 0.5), rc::gen::element(2.0, 1.0, 3.0, 0.5),
                                     rc::gen::element(60.0, 90.0, 40.0), rc::gen::element(0.2, 0.05, 0.4, 0.7),
                                     rc::gen::element(0.2, 0.05, 0.5), rc::gen::element(20.0, 8.0, 40.0),
                                     rc::gen::element(8.0, 3.0, 20.0), rc::gen::element(6.0, 1.0, 15.0),
                                     rc::gen::element(2.0, 0.5, 5.0), rc::gen::element(1.0, 0.3, 1.4), drawn_origin()),
                      [](const auto& tuple) {
                        ClippedWallDraw d;
                        std::tie(d.radius, d.near, d.hfov_deg, d.past, d.thickness, d.half_width, d.height, d.behind,
                                 d.side, d.target_height, d.origin) = tuple;
                        return d;
                      });
}

}  // namespace cullcheck::properties
