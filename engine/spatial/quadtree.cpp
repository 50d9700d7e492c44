#include "engine/spatial/quadtree.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace cullcheck {

Quadtree::Quadtree(const Scene& scene, std::uint32_t leaf_size, std::uint32_t max_depth) {
  const std::size_t n = scene.buildings.size();
  order_.resize(n);
  centres_.resize(n);
  Box2 square;
  for (std::uint32_t i = 0; i < n; ++i) {
    order_[i] = i;
    centres_[i] = scene.buildings[i].bounds.plan().center();
    square.extend(centres_[i]);
    const Box3& b = scene.buildings[i].bounds;
    extent_.extend({b.lo.x, b.lo.y, std::min(b.lo.z, 0.0)});
    extent_.extend(b.hi);
  }
  if (n == 0) square = {{0, 0}, {0, 0}};
  const double side = std::max(square.hi.x - square.lo.x, square.hi.y - square.lo.y);
  square.hi = square.lo + Vec2{side, side};
  cells_.push_back({});
  cells_[0].first = 0;
  cells_[0].last = static_cast<std::uint32_t>(n);
  build(0, square, 0, scene, std::max(1u, leaf_size), max_depth);
  centres_.clear();
  centres_.shrink_to_fit();
  by_height_ = {};
  scratch_ = {};
}

void Quadtree::build(std::uint32_t cell, Box2 square, std::uint32_t depth, const Scene& scene, std::uint32_t leaf_size,
                     std::uint32_t max_depth) {
  const std::uint32_t first = cells_[cell].first, last = cells_[cell].last;
  for (std::uint32_t i = first; i < last; ++i) {
    const Building& b = scene.buildings[order_[i]];
    cells_[cell].bounds.extend(b.bounds.plan());
    cells_[cell].max_height = std::max(cells_[cell].max_height, b.height);
  }
  if (last - first <= leaf_size || depth >= max_depth) {
    split_by_height(cell, scene);
    return;
  }
  // Split the building range into the four quadrants by centre; a stable partition keeps the
  // order (and so every traversal) deterministic.
  const Vec2 mid = square.center();
  auto begin = order_.begin() + first, end = order_.begin() + last;
  auto west = [&](std::uint32_t i) { return centres_[i].x < mid.x; };
  auto south = [&](std::uint32_t i) { return centres_[i].y < mid.y; };
  auto split_x = std::stable_partition(begin, end, west);
  auto split_sw = std::stable_partition(begin, split_x, south);
  auto split_se = std::stable_partition(split_x, end, south);
  const std::uint32_t bounds[5] = {first, static_cast<std::uint32_t>(split_sw - order_.begin()),
                                   static_cast<std::uint32_t>(split_x - order_.begin()),
                                   static_cast<std::uint32_t>(split_se - order_.begin()), last};
  const Box2 squares[4] = {{square.lo, mid},
                           {{square.lo.x, mid.y}, {mid.x, square.hi.y}},
                           {{mid.x, square.lo.y}, {square.hi.x, mid.y}},
                           {mid, square.hi}};
  // Quadrant order above: SW, NW, SE, NE (west half first, then south within each half).
  const std::uint32_t child = static_cast<std::uint32_t>(cells_.size());
  cells_[cell].first_child = child;
  for (int q = 0; q < 4; ++q) {
    Cell c;
    c.first = bounds[q];
    c.last = bounds[q + 1];
    cells_.push_back(c);
  }
  for (int q = 0; q < 4; ++q) build(child + q, squares[q], depth + 1, scene, leaf_size, max_depth);
  split_by_height(cell, scene);
}

// Tallest first (ties by scene index, so the split is deterministic); the tall set grows one
// building at a time and the rest's height is the next building's. Volume = tall box x max
// height + whole box x rest height; taking every building (today's single box) is a candidate,
// so the chosen pair never encloses more than it. A leaf sorts its few buildings; an inner cell
// merges its children's sorted runs (built just before), so the whole tree costs one sort.
void Quadtree::split_by_height(std::uint32_t index, const Scene& scene) {
  Cell& cell = cells_[index];
  if (by_height_.size() != order_.size()) by_height_.resize(order_.size()), scratch_.resize(order_.size());
  const auto taller = [](const Ranked& a, const Ranked& b) { return a.height != b.height ? a.height > b.height : a.index < b.index; };
  const auto run = by_height_.begin();
  if (cell.leaf()) {
    for (std::uint32_t k = cell.first; k < cell.last; ++k) {
      const Building& b = scene.buildings[order_[k]];
      by_height_[k] = {b.height, order_[k], b.bounds.plan()};
    }
    std::sort(run + cell.first, run + cell.last, taller);
  } else {
    const Cell* child = &cells_[cell.first_child];
    const auto out = scratch_.begin();
    std::merge(run + child[0].first, run + child[0].last, run + child[1].first, run + child[1].last, out + child[0].first, taller);
    std::merge(run + child[2].first, run + child[2].last, run + child[3].first, run + child[3].last, out + child[2].first, taller);
    std::merge(out + child[0].first, out + child[2].first, out + child[2].first, out + child[3].last, run + cell.first, taller);
  }
  const auto area = [](const Box2& b) { return b.empty() ? 0.0 : (b.hi.x - b.lo.x) * (b.hi.y - b.lo.y); };
  Box2 tall;
  double least = HUGE_VAL;
  for (std::uint32_t k = cell.first; k < cell.last; ++k) {
    tall.extend(by_height_[k].box);
    const bool rest = k + 1 < cell.last;
    const double rest_height = rest ? by_height_[k + 1].height : 0.0;
    const double volume = area(tall) * cell.max_height + area(cell.bounds) * rest_height;
    if (volume < least) {
      least = volume;
      cell.tall_bounds = tall;
      cell.rest_height = rest ? rest_height : -std::numeric_limits<double>::infinity();
    }
  }
}

std::string Quadtree::check_invariants(const Scene& scene) const {
  for (std::size_t c = 0; c < cells_.size(); ++c) {
    const Cell& cell = cells_[c];
    for (std::uint32_t i = cell.first; i < cell.last; ++i) {
      const Building& b = scene.buildings[order_[i]];
      const Box2 box = b.bounds.plan();
      if (!cell.bounds.contains(box.lo) || !cell.bounds.contains(box.hi))
        return "cell " + std::to_string(c) + " does not enclose building " + std::to_string(b.id);
      if (b.height > cell.max_height)
        return "cell " + std::to_string(c) + " max height is below building " + std::to_string(b.id);
      const bool tall = cell.tall_bounds.contains(box.lo) && cell.tall_bounds.contains(box.hi);
      if (!tall && !(b.height <= cell.rest_height))
        return "cell " + std::to_string(c) + " height split leaves out building " + std::to_string(b.id);
    }
    if (!cell.tall_bounds.empty() && (!cell.bounds.contains(cell.tall_bounds.lo) || !cell.bounds.contains(cell.tall_bounds.hi)))
      return "cell " + std::to_string(c) + " tall box reaches outside its bounds";
    if (!cell.leaf()) {
      if (cells_[cell.first_child].first != cell.first || cells_[cell.first_child + 3].last != cell.last)
        return "cell " + std::to_string(c) + " children do not cover its building range";
      for (int q = 0; q < 3; ++q)
        if (cells_[cell.first_child + q].last != cells_[cell.first_child + q + 1].first)
          return "cell " + std::to_string(c) + " children ranges are not contiguous";
    }
  }
  std::vector<std::uint32_t> sorted = order_;
  std::sort(sorted.begin(), sorted.end());
  for (std::uint32_t i = 0; i < sorted.size(); ++i)
    if (sorted[i] != i) return "building order is not a permutation";
  return {};
}

}  // namespace cullcheck
