// The server's line-of-sight filter (issue 17: VbAoI's traffic against its physical limit).
//
// VbAoI groups clients by node: a listener receives every update published in a node of its
// PVSn, whether or not it can see the sender from where it stands. The server knows more than
// the nodes: every update carries the sender's position, and the listener's own last update
// told where it was a few ticks ago. This filter lets the server drop an update whose sender
// provably cannot be seen from any place the listener may be: all of the disc D(q, ρ) around the
// listener's last known position q, ρ the distance it may have walked since.
//
// Both avatars' eyes stand at the same height h above flat ground (the simulation's model), so a
// line of sight is a horizontal segment at height h: it is blocked exactly when it crosses a
// prism whose base lies below h and whose top lies above it. `hidden(p, q, ρ)` is true only when
// every segment from p to a point of D crosses such a prism: the directions from p towards D
// (an interval of half-width asin(ρ / |q - p|)) are covered by prisms each of which every ray of
// its part of the interval enters nearer than |q - p| - ρ, the nearest that any point of D lies.
// A convex prism's entry distance along a fan of rays is largest at the fan's two edges or at
// one of its vertices inside the fan (along each edge of the near chain the distance is
// d / cos(angle), convex in the angle), so those are the points compared. Prisms reaching behind
// p are clipped to the half-plane in front of it (a part of an occluder still occludes).
// Terrain and mesh objects are never counted as occluders, which only lets more through.
//
// Exactness: the margins (1e-9 relative on angles and distances) lie far above the rounding of
// the values compared. Each prism counts only by its part 1 cm (plus 1e-6 of its coordinates)
// inside its walls: the oracle casts its line of sight in single precision, and a sight line
// that cuts a corner by micrometres is one it may see past. The oracle (properties/vbaoi_test.cpp,
// the report's runs) holds the filter to zero missed updates.
#pragma once

#include <cstdint>
#include <vector>

#include "core/scene.hpp"

namespace cullcheck::vbaoi {

class SightFilter {
 public:
  // `eye_height`: both eyes' height above the ground; `cell`: the side (m) of the grid that finds
  // the prisms near a line of sight.
  SightFilter(const Scene& scene, double eye_height, double cell = 16.0);

  // True only when no point of the disc of radius `radius` around `to` (at eye height) sees the
  // eye at `from`; false when unsure.
  bool hidden(Vec2 from, Vec2 to, double radius);

  // Prisms tested, over every call (a cost figure for tests and reports).
  std::uint64_t prisms_tested() const { return prisms_tested_; }

 private:
  struct Blocker {
    std::vector<Vec2> ring;  // convex, counter-clockwise
  };
  struct Interval {
    double lo, hi;
  };
  // The part [lo, hi] of [-limit, limit] (tangents of angles from the line of sight) that
  // `blocker` covers nearer than `reach`, in the frame (u, v) at `from`; false when none.
  bool covers(const Blocker& blocker, Vec2 from, Vec2 u, Vec2 v, double limit, double reach, Interval& out);

  std::vector<Blocker> blockers_;
  std::vector<std::vector<std::uint32_t>> cells_;  // per grid cell: blockers whose box meets it
  Vec2 origin_;
  double cell_ = 16.0;
  std::int64_t columns_ = 0, rows_ = 0;
  std::vector<std::uint32_t> seen_;  // per blocker: the call that last tested it
  std::uint32_t call_ = 0;
  std::vector<Vec2> clipped_;
  std::vector<Interval> intervals_;
  std::uint64_t prisms_tested_ = 0;
};

}  // namespace cullcheck::vbaoi
