#include "engine/polar_diagram/exact_sign.hpp"

#include <array>
#include <cmath>
#include <cstddef>

namespace cullcheck::polar {
namespace {

constexpr double kEps = 0x1p-53;

// x + y = s + e exactly (Knuth's two-sum).
void two_sum(double x, double y, double& s, double& e) {
  s = x + y;
  const double bv = s - x;
  const double av = s - bv;
  e = (x - av) + (y - bv);
}

// The exact sign of a sum of doubles: grown into a non-overlapping expansion (Shewchuk's
// Grow-Expansion), whose largest non-zero component carries the sign.
template <std::size_t N>
int expansion_sign(const std::array<double, N>& terms) {
  std::array<double, N> h{};
  std::size_t len = 0;
  for (double t : terms) {
    double q = t;
    std::size_t out = 0;
    for (std::size_t i = 0; i < len; ++i) {
      double s, e;
      two_sum(q, h[i], s, e);
      q = s;
      if (e != 0.0) h[out++] = e;
    }
    h[out++] = q;
    len = out;
  }
  for (std::size_t i = len; i-- > 0;)
    if (h[i] != 0.0) return h[i] > 0 ? 1 : -1;
  return 0;
}

// The exact sign of the cross or dot product of a - b and c - d: each product of differences
// expanded into four products of inputs, each split by fma into two doubles.
int exact_pair(Vec2 a, Vec2 b, Vec2 c, Vec2 d, bool cross) {
  // (a1 - b1)(c1 - d1) = a1 c1 - a1 d1 - b1 c1 + b1 d1
  // cross: (ax - bx)(cy - dy) + (-ay + by)(cx - dx); dot: (ax - bx)(cx - dx) + (ay - by)(cy - dy).
  const double u1[2] = {a.x, -b.x};
  const double v1[2] = {cross ? c.y : c.x, cross ? -d.y : -d.x};
  const double u2[2] = {cross ? -a.y : a.y, cross ? b.y : -b.y};
  const double v2[2] = {cross ? c.x : c.y, cross ? -d.x : -d.y};
  std::array<double, 16> terms{};
  std::size_t k = 0;
  for (int i = 0; i < 2; ++i)
    for (int j = 0; j < 2; ++j) {
      const double p = u1[i] * v1[j];
      terms[k++] = p;
      terms[k++] = std::fma(u1[i], v1[j], -p);
      const double q = u2[i] * v2[j];
      terms[k++] = q;
      terms[k++] = std::fma(u2[i], v2[j], -q);
    }
  return expansion_sign(terms);
}

int filtered(double l, double r, double value) {
  // Four rounded differences, two rounded products and one rounded sum: 8 eps of the
  // magnitudes is a safe bound for the error of `value` (and overflow-free for scene metres).
  const double bound = 8 * kEps * (std::abs(l) + std::abs(r));
  if (value > bound) return 1;
  if (value < -bound) return -1;
  return 2;  // undecided
}

}  // namespace

int cross_sign(Vec2 a, Vec2 b, Vec2 c, Vec2 d) {
  const double l = (a.x - b.x) * (c.y - d.y);
  const double r = (a.y - b.y) * (c.x - d.x);
  const int s = filtered(l, r, l - r);
  return s != 2 ? s : exact_pair(a, b, c, d, true);
}

int dot_sign(Vec2 a, Vec2 b, Vec2 c, Vec2 d) {
  const double l = (a.x - b.x) * (c.x - d.x);
  const double r = (a.y - b.y) * (c.y - d.y);
  const int s = filtered(l, -r, l + r);
  return s != 2 ? s : exact_pair(a, b, c, d, false);
}

}  // namespace cullcheck::polar
