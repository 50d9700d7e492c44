#include "engine/shrinking/circle_tiling.hpp"

#include <algorithm>
#include <cmath>

namespace cullcheck {

Vec2 CircleTiling::nearest_centre(Vec2 p) const {
  // The nearest lattice point lies in one of the two rows around p; within a row, one of the
  // two columns around p's x.
  const auto j0 = static_cast<std::int64_t>(std::floor(p.y / row_step()));
  Vec2 best{};
  double best_d = HUGE_VAL;
  for (std::int64_t j = j0; j <= j0 + 1; ++j) {
    const double shift = 0.5 * static_cast<double>(j & 1);
    const auto i0 = static_cast<std::int64_t>(std::floor(p.x / spacing() - shift));
    for (std::int64_t i = i0; i <= i0 + 1; ++i) {
      const Vec2 c = centre(i, j);
      const double d = length(c - p);
      if (d < best_d) best_d = d, best = c;
    }
  }
  return best;
}

double distance_to_convex(const std::vector<Vec2>& ring, Vec2 p) {
  bool inside = true;
  double best = HUGE_VAL;
  for (std::size_t i = 0, j = ring.size() - 1; i < ring.size(); j = i++) {
    if (cross(ring[i] - ring[j], p - ring[j]) < 0.0) inside = false;
    best = std::min(best, distance_to_segment(p, ring[j], ring[i]));
  }
  return inside ? 0.0 : best;
}

std::vector<Vec2> CircleTiling::centres_covering(const std::vector<Vec2>& ring) const {
  Box2 box;
  for (Vec2 v : ring) box.extend(v);
  const auto j_lo = static_cast<std::int64_t>(std::floor((box.lo.y - radius) / row_step()));
  const auto j_hi = static_cast<std::int64_t>(std::ceil((box.hi.y + radius) / row_step()));
  std::vector<Vec2> out;
  for (std::int64_t j = j_lo; j <= j_hi; ++j) {
    const double shift = 0.5 * static_cast<double>(j & 1);
    const auto i_lo = static_cast<std::int64_t>(std::floor((box.lo.x - radius) / spacing() - shift));
    const auto i_hi = static_cast<std::int64_t>(std::ceil((box.hi.x + radius) / spacing() - shift));
    std::vector<Vec2> row;
    for (std::int64_t i = i_lo; i <= i_hi; ++i) {
      const Vec2 c = centre(i, j);
      // A centre whose disc misses the cell is nobody's nearest centre inside it.
      if (distance_to_convex(ring, c) <= radius) row.push_back(c);
    }
    if ((j - j_lo) % 2 == 1) std::reverse(row.begin(), row.end());
    out.insert(out.end(), row.begin(), row.end());
  }
  return out;
}

}  // namespace cullcheck
