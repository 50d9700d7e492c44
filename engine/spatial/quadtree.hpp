// 2D quadtree over the plan view (thesis ch. 3.1.1): each cell keeps the maximum building
// height inside it or its descendants, so a whole cell can be culled at once.
//
// A building is stored in the leaf that contains its footprint's bounding-box centre; each
// cell's `bounds` is the union of its buildings' footprint boxes (tight, not the square cell),
// so every cell test is conservative for everything below it.
//
// One box up to the tallest building is loose where a cell holds a few tall buildings among
// low ones: on the default city's street walk, OH(OS) entered 23 cells a frame that led to no
// visible building, and a test of each cell's exact box (bin by bin) would have culled 1 of
// them, a test of its buildings one by one 20. So each cell also splits its buildings by
// height into two boxes, the tall ones' box up to the tallest and the whole cell up to the
// rest's height, at the split where the two enclose the least volume; a cell is hidden when
// both are (engine/horizon/horizon_sweep.hpp, cell_hidden).
#pragma once

#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "core/scene.hpp"

namespace cullcheck {

class Quadtree {
 public:
  struct Cell {
    Box2 bounds;              // tight plan-view bounds of the buildings below
    double max_height = 0.0;  // highest building below
    // The height split: every building below lies in `tall_bounds` (within `bounds`) or reaches
    // at most `rest_height`; −inf when every building is in `tall_bounds` (no rest).
    Box2 tall_bounds;
    double rest_height = -std::numeric_limits<double>::infinity();
    bool has_rest() const { return rest_height > -std::numeric_limits<double>::infinity(); }
    std::uint32_t first_child = 0;  // children are first_child .. first_child + 3; 0 for a leaf
    std::uint32_t first = 0, last = 0;  // building range [first, last) in buildings()
    bool leaf() const { return first_child == 0; }
  };

  Quadtree(const Scene& scene, std::uint32_t leaf_size = 8, std::uint32_t max_depth = 24);

  const std::vector<Cell>& cells() const { return cells_; }  // cells()[0] is the root
  // Every building's bounds and the ground (z = 0) under them: each box a sweep tests (a
  // building's, or a cell's from the ground to its highest building) lies within it.
  const Box3& extent() const { return extent_; }
  // Scene building indices, ordered so that each cell's buildings are contiguous.
  const std::vector<std::uint32_t>& buildings() const { return order_; }
  // Calls on_cell(child index) for each non-empty child of an inner cell, or on_building(scene
  // building index) for each building of a leaf: one step of a front-to-back traversal.
  template <class OnCell, class OnBuilding>
  void for_each_child(const Cell& cell, OnCell&& on_cell, OnBuilding&& on_building) const {
    if (cell.leaf()) {
      for (std::uint32_t i = cell.first; i < cell.last; ++i) on_building(order_[i]);
      return;
    }
    for (std::uint32_t c = cell.first_child; c < cell.first_child + 4; ++c)
      if (cells_[c].last > cells_[c].first) on_cell(c);
  }
  // Structure invariant: bounds and max heights enclose every building below, so does each
  // cell's height split, ranges nest.
  std::string check_invariants(const Scene& scene) const;

 private:
  void build(std::uint32_t cell, Box2 square, std::uint32_t depth, const Scene& scene, std::uint32_t leaf_size,
             std::uint32_t max_depth);
  // Sorts the cell's range of by_height_ (merging its children's sorted runs), then splits.
  void split_by_height(std::uint32_t cell, const Scene& scene);
  std::vector<Cell> cells_;
  Box3 extent_;
  std::vector<std::uint32_t> order_;
  std::vector<Vec2> centres_;
  // During the build: each built cell's buildings, tallest first, in the cell's range of order_
  // (height, scene index and plan box copied, so merging and scanning read memory in order).
  struct Ranked {
    double height;
    std::uint32_t index;
    Box2 box;
  };
  std::vector<Ranked> by_height_, scratch_;
};

}  // namespace cullcheck
