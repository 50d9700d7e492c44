#include "core/navigable_region.hpp"

#include <algorithm>
#include <cmath>

namespace cullcheck {

std::optional<std::pair<Vec2, Vec2>> shared_edge(const std::vector<Vec2>& a, const std::vector<Vec2>& b,
                                                 double tolerance) {
  std::optional<std::pair<Vec2, Vec2>> best;
  double best_length = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    const Vec2 p = a[i], q = a[(i + 1) % a.size()];
    const Vec2 d = q - p;
    const double len = length(d);
    if (len == 0.0) continue;
    const Vec2 u = d * (1.0 / len);
    for (std::size_t j = 0; j < b.size(); ++j) {
      const Vec2 r = b[j], s = b[(j + 1) % b.size()];
      // Both ends of b's edge on a's edge line, and the edges running opposite ways (two
      // counter-clockwise rings meet along an edge traversed in opposite directions).
      if (std::abs(cross(u, r - p)) > tolerance || std::abs(cross(u, s - p)) > tolerance) continue;
      if (dot(s - r, u) >= 0.0) continue;
      const double lo = std::max(0.0, dot(s - p, u)), hi = std::min(len, dot(r - p, u));
      if (hi - lo > tolerance && hi - lo > best_length) {
        best_length = hi - lo;
        best = std::pair{p + u * lo, p + u * hi};
      }
    }
  }
  return best;
}

bool ring_contains(const std::vector<Vec2>& ring, Vec2 p, double tolerance) {
  for (std::size_t i = 0; i < ring.size(); ++i) {
    const Vec2 a = ring[i], d = ring[(i + 1) % ring.size()] - a;
    const double len = length(d);
    if (len == 0.0) continue;
    if (cross(d, p - a) / len < -tolerance) return false;  // right of a counter-clockwise edge: outside
  }
  return !ring.empty();
}

Vec2 random_point_in(const std::vector<Vec2>& ring, Random& rng) {
  Box2 box;
  for (Vec2 v : ring) box.extend(v);
  for (int attempt = 0; attempt < 64; ++attempt) {
    const Vec2 p{rng.uniform_real(box.lo.x, box.hi.x), rng.uniform_real(box.lo.y, box.hi.y)};
    if (ring_contains(ring, p, 0.0)) return p;
  }
  Vec2 c{0, 0};
  for (Vec2 v : ring) c = c + v;
  return c * (1.0 / static_cast<double>(ring.size()));
}

std::int64_t locate_region(const std::vector<NavigableRegion>& regions, Vec2 point, double tolerance) {
  for (const NavigableRegion& r : regions)
    if (ring_contains(r.ring, point, tolerance)) return r.id;
  return -1;
}

}  // namespace cullcheck
