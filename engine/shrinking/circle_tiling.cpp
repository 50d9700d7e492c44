#include "engine/shrinking/circle_tiling.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace cullcheck {
namespace {

// A lattice coordinate (a point's coordinate over the row step or the spacing) as an integer
// index. Converting a NaN, an infinity or a value beyond int64's range is undefined behaviour;
// beyond 2^53 the lattice is not even representable. Both are bad input (a point or ε that
// cannot be tiled), reported as such.
std::int64_t lattice_index(double v, const char* what) {
  if (!(std::abs(v) <= 9007199254740992.0))
    throw std::invalid_argument(std::string("circle tiling: ") + what + " = " + std::to_string(v) +
                                " lattice steps, not a representable lattice index (coordinates too large for ε?)");
  return static_cast<std::int64_t>(v);
}

}  // namespace

Vec2 CircleTiling::nearest_centre(Vec2 p) const {
  // The nearest lattice point lies in one of the two rows around p; within a row, one of the
  // two columns around p's x.
  const auto j0 = lattice_index(std::floor(p.y / row_step()), "row of y");
  Vec2 best{};
  double best_d = HUGE_VAL;
  for (std::int64_t j = j0; j <= j0 + 1; ++j) {
    const double shift = 0.5 * static_cast<double>(j & 1);
    const auto i0 = lattice_index(std::floor(p.x / spacing() - shift), "column of x");
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
  const auto j_lo = lattice_index(std::floor((box.lo.y - radius) / row_step()), "lowest row");
  const auto j_hi = lattice_index(std::ceil((box.hi.y + radius) / row_step()), "highest row");
  std::vector<Vec2> out;
  for (std::int64_t j = j_lo; j <= j_hi; ++j) {
    const double shift = 0.5 * static_cast<double>(j & 1);
    const auto i_lo = lattice_index(std::floor((box.lo.x - radius) / spacing() - shift), "lowest column");
    const auto i_hi = lattice_index(std::ceil((box.hi.x + radius) / spacing() - shift), "highest column");
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
