// How often a property's cases reach the hard cases (issue "Trust the gate"): a property that
// passes only because its cases never get near what breaks culling proves nothing. Each case is
// classified on four features, each decided from the scene, the camera, the oracle's answer and
// the PVSs, with plan geometry written here (shared with neither the engine nor the oracle):
//  - horizon beyond frustum: the horizon method's PVS lacks something frustum culling keeps
//    (occlusion culling did work in this case);
//  - narrow gap: the oracle's witness ray of some visible building runs between two buildings
//    standing less than 1 m apart across it (the sum of its plan clearances to the nearest
//    building rising above it on its left and on its right is below 1 m); decided on ray-sampled
//    answers only (an exact_2d answer keeps no rays and counts as not reaching it);
//  - eye near wall: the eye's plan distance to a footprint of a building taller than the eye is
//    below 1 m;
//  - steep: a perspective camera pitched or rolled by more than 30 degrees.
// A property prints the shares and asserts each is above a floor set from measurement.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

#include "core/camera.hpp"
#include "core/scene.hpp"
#include "oracle/oracle.hpp"

namespace cullcheck {

inline constexpr double kNarrowGapMetres = 1.0;
inline constexpr double kNearWallMetres = 1.0;
inline constexpr double kSteepRadians = 30.0 * kPi / 180.0;

enum class HardCase : int { horizon_beyond_frustum, narrow_gap, eye_near_wall, steep, count };
inline constexpr std::array<const char*, 4> kHardCaseNames{"horizon culls beyond the frustum", "visible through a gap < 1 m",
                                                          "eye within 1 m of a wall", "pitch or roll > 30 degrees"};

namespace coverage_detail {

// Plan distance between segments [a, b] and [c, d] (0 when they cross), and the parameter along
// [a, b] of the closest point.
struct SegmentDistance {
  double distance = 0.0;
  double s = 0.0;  // along [a, b], in [0, 1]
  Vec2 other;      // the closest point on [c, d]
};
inline Vec2 closest_on(Vec2 p, Vec2 a, Vec2 b, double* t_out = nullptr) {
  const Vec2 d = b - a;
  const double len2 = dot(d, d);
  const double t = len2 > 0 ? std::clamp(dot(p - a, d) / len2, 0.0, 1.0) : 0.0;
  if (t_out) *t_out = t;
  return a + d * t;
}
inline bool segments_cross(Vec2 a, Vec2 b, Vec2 c, Vec2 d) {
  const double d1 = cross(b - a, c - a), d2 = cross(b - a, d - a), d3 = cross(d - c, a - c), d4 = cross(d - c, b - c);
  return ((d1 > 0) != (d2 > 0)) && ((d3 > 0) != (d4 > 0)) && d1 != 0 && d2 != 0 && d3 != 0 && d4 != 0;
}
inline SegmentDistance segment_distance(Vec2 a, Vec2 b, Vec2 c, Vec2 d) {
  if (segments_cross(a, b, c, d)) return {0.0, 0.0, c};
  SegmentDistance best{std::numeric_limits<double>::infinity(), 0.0, c};
  auto consider = [&](double dist, double s, Vec2 other) {
    if (dist < best.distance) best = {dist, s, other};
  };
  double t = 0.0;
  Vec2 q = closest_on(a, c, d);
  consider(length(q - a), 0.0, q);
  q = closest_on(b, c, d);
  consider(length(q - b), 1.0, q);
  q = closest_on(c, a, b, &t);
  consider(length(q - c), t, c);
  q = closest_on(d, a, b, &t);
  consider(length(q - d), t, d);
  return best;
}

inline bool inside_ring(const std::vector<Vec2>& ring, Vec2 p) {
  bool in = false;
  for (std::size_t i = 0, j = ring.size() - 1; i < ring.size(); j = i++)
    if ((ring[i].y > p.y) != (ring[j].y > p.y) &&
        p.x < (ring[j].x - ring[i].x) * (p.y - ring[i].y) / (ring[j].y - ring[i].y) + ring[i].x)
      in = !in;
  return in;
}

// Sum of the plan clearances of `ray` to the nearest building rising above it on each side
// (infinite when one side has none within `reach`). Buildings the ray crosses in plan are passed
// over (or clipped by the near plane) and do not bound the gap; `hit` is the building it ends on.
inline double gap_across(const Scene& scene, const oracle::WitnessRay& ray, ObjectId hit, double reach) {
  const Vec3 start = ray.origin + ray.direction * ray.t_near;
  const Vec2 a = plan(start), b = plan(ray.hit_point), along = b - a;
  if (length(along) < 1e-9) return std::numeric_limits<double>::infinity();
  const Box2 box{{std::min(a.x, b.x) - reach, std::min(a.y, b.y) - reach}, {std::max(a.x, b.x) + reach, std::max(a.y, b.y) + reach}};
  double left = std::numeric_limits<double>::infinity(), right = left;
  for (const Building& o : scene.buildings) {
    if (o.id == hit) continue;
    const Box2 ob = o.bounds.plan();
    if (ob.lo.x > box.hi.x || ob.hi.x < box.lo.x || ob.lo.y > box.hi.y || ob.hi.y < box.lo.y) continue;
    SegmentDistance best{std::numeric_limits<double>::infinity(), 0.0, {}};
    for (std::size_t i = 0; i < o.footprint.size(); ++i) {
      const SegmentDistance d = segment_distance(a, b, o.footprint[i], o.footprint[(i + 1) % o.footprint.size()]);
      if (d.distance < best.distance) best = d;
    }
    if (best.distance == 0.0 || best.distance > reach || inside_ring(o.footprint, a)) continue;  // crossed: passed over
    const double z = start.z + (ray.hit_point.z - start.z) * best.s;
    if (o.height <= z) continue;  // lower than the ray where it passes: no wall beside it
    double& side = cross(along, best.other - (a + along * best.s)) > 0 ? left : right;
    side = std::min(side, best.distance);
  }
  return left + right;
}

}  // namespace coverage_detail

// The features of one case. `horizon_pvs` is empty when the method under test has no horizon.
inline std::array<bool, 4> hard_case_features(const Scene& scene, const Camera& camera, const oracle::OracleAnswer& seen,
                                              const std::vector<ObjectId>* horizon_pvs, const std::vector<ObjectId>* frustum_pvs) {
  std::array<bool, 4> f{};
  if (horizon_pvs && frustum_pvs)
    f[int(HardCase::horizon_beyond_frustum)] =
        !std::includes(horizon_pvs->begin(), horizon_pvs->end(), frustum_pvs->begin(), frustum_pvs->end());
  if (seen.sampling)
    for (const auto& [id, ray] : seen.sampling->witnesses)
      if (coverage_detail::gap_across(scene, ray, id, kNarrowGapMetres) < kNarrowGapMetres) {
        f[int(HardCase::narrow_gap)] = true;
        break;
      }
  const Vec2 eye = plan(camera.position);
  for (const Building& b : scene.buildings) {
    if (b.height <= camera.position.z) continue;
    double d = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < b.footprint.size(); ++i)
      d = std::min(d, length(coverage_detail::closest_on(eye, b.footprint[i], b.footprint[(i + 1) % b.footprint.size()]) - eye));
    if (d < kNearWallMetres) {
      f[int(HardCase::eye_near_wall)] = true;
      break;
    }
  }
  const double roll = std::remainder(camera.roll, kTwoPi);
  f[int(HardCase::steep)] = !camera.omnidirectional() && !camera.orthographic() &&
                            (std::abs(camera.pitch) > kSteepRadians || std::abs(roll) > kSteepRadians);
  return f;
}

// Shares of a property's cases that reach each hard case.
struct HardCaseCoverage {
  std::size_t cases = 0;
  std::array<std::size_t, 4> reached{};

  void add(const std::array<bool, 4>& f) {
    ++cases;
    for (int k = 0; k < 4; ++k) reached[k] += f[k];
  }
  double share(HardCase k) const { return cases ? double(reached[int(k)]) / double(cases) : 0.0; }
  // One line, e.g. "oh_os_conservative over 500 cases: horizon culls beyond the frustum 41.2%, ...".
  std::string summary(const std::string& what) const {
    std::string s = what + " over " + std::to_string(cases) + " cases:";
    char buf[96];
    for (int k = 0; k < 4; ++k) {
      std::snprintf(buf, sizeof buf, "%s %s %.1f%%", k ? "," : "", kHardCaseNames[k], 100.0 * share(HardCase(k)));
      s += buf;
    }
    return s;
  }
};

}  // namespace cullcheck
