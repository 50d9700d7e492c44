// atan2 for the horizon's hot path: every azimuth span costs two (issue 17 measured libm's atan2,
// with its rounding-mode save and restore, at 15% of a guarded ΔH frame).
//
// Range reduction to t = min(|x|, |y|) / max(|x|, |y|) in [0, 1], then atan(t) = atan(c) +
// atan(u) with c the nearest sixteenth and u = (t − c) / (1 + t·c), |u| <= 1/32, where the odd
// Taylor series to u^11 is exact to a few 1e-19. Rounding of the division, the table and the
// octant's π/2 − r or π − r keeps the result within 1e-15 rad of the true angle (a property in
// horizon_structure_test holds it to 2e-15 of libm's atan2): about a thousandth of
// kAngularSlack (1e-12), which every span the horizon rounds to bins carries already.
//
// Engine-only: the oracle keeps libm's atan2, so the two share no angle code.
#pragma once

#include <cmath>

#include "core/geometry.hpp"

namespace cullcheck {

namespace detail {
// atan(k / 16), k = 0..16, correctly rounded.
inline constexpr double kAtanOfSixteenths[17] = {
    0.0,                 0.06241880999595735, 0.12435499454676144, 0.18534794999569476, 0.24497866312686414,
    0.3028848683749714,  0.35877067027057225, 0.4124104415973873,  0.4636476090008061,  0.5123894603107377,
    0.5585993153435624,  0.6022873461349642,  0.6435011087932844,  0.6823165548747481,  0.7188299996216245,
    0.7531512809621944,  0.7853981633974483};
}  // namespace detail

// atan2(y, x) in [−π, π]; libm's for zero, infinite or NaN arguments (their conventions).
inline double fast_atan2(double y, double x) {
  const double ax = std::abs(x), ay = std::abs(y);
  const double big = ax > ay ? ax : ay, small = ax > ay ? ay : ax;
  if (!(small >= 0.0) || !(big > 0.0) || !(big < HUGE_VAL)) return std::atan2(y, x);  // NaN fails a test
  const double t = small / big;
  const int k = static_cast<int>(t * 16.0 + 0.5);
  const double c = k * (1.0 / 16.0);
  const double u = (t - c) / (1.0 + t * c);
  const double u2 = u * u;
  const double series =
      u * (1.0 + u2 * (-1.0 / 3 + u2 * (1.0 / 5 + u2 * (-1.0 / 7 + u2 * (1.0 / 9 + u2 * (-1.0 / 11))))));
  double r = detail::kAtanOfSixteenths[k] + series;
  if (ay > ax) r = kPi / 2 - r;
  if (x < 0.0) r = kPi - r;
  return std::signbit(y) ? -r : r;
}

// azimuth_of (core/geometry.hpp) with fast_atan2: [0, 2π).
inline double fast_azimuth(Vec2 d) {
  double a = fast_atan2(d.y, d.x);
  if (a < 0.0) a += kTwoPi;
  return a >= kTwoPi ? 0.0 : a;
}

}  // namespace cullcheck
