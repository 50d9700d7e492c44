// Angle helpers for camera paths: azimuth wrap-around and smooth blends. Polynomial blends
// (not trigonometric ones) keep paths identical across maths libraries.
#pragma once

#include <algorithm>
#include <cmath>

#include "core/geometry.hpp"

namespace cullcheck::generators {

inline double radians(double degrees) { return degrees * (kPi / 180.0); }

// Into [0, 2*pi), the design's azimuth range (fmod is exact).
inline double wrap_azimuth(double a) {
  a = std::fmod(a, kTwoPi);
  if (a < 0.0) a += kTwoPi;
  return a >= kTwoPi ? 0.0 : a;
}

// The signed turn from azimuth `from` to `to`, in (-pi, pi]: the short way round, across the
// 0 / 2*pi seam when that is shorter.
inline double shortest_turn(double from, double to) {
  double d = std::fmod(to - from, kTwoPi);
  if (d <= -kPi) d += kTwoPi;
  if (d > kPi) d -= kTwoPi;
  return d;
}

// C1 ease from 0 to 1 over t in [0, 1]: zero angular speed at both ends of a turn.
constexpr double smoothstep(double t) {
  t = t < 0.0 ? 0.0 : (t > 1.0 ? 1.0 : t);
  return t * t * (3.0 - 2.0 * t);
}

// A smooth wave of period 1 with values in [-1, 1] made of two parabolas (C1): the walker's sway.
inline double parabolic_wave(double phase) {
  const double u = phase - std::floor(phase);
  return u < 0.5 ? 16.0 * u * (0.5 - u) : -16.0 * (u - 0.5) * (1.0 - u);
}

}  // namespace cullcheck::generators
