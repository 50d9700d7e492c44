// The radar's preprocessing (thesis ch. 3.3.3): the terrain's triangles (and its buildings')
// scattered into the cells
// of a regular grid laid over its plan, a triangle in every cell it meets; each cell's highest
// value precomputed and its triangles sorted from highest to lowest.
//
// "Meets" is overlap with positive area (a triangle touching a cell along its edge only is not
// listed there), decided by separating axes in the plan; rounding can only list a triangle in
// one more cell, never drop one. A cell's highest value is the highest vertex of the triangles
// it lists, so it bounds every point of them that lies in the cell; an empty cell (all its
// triangles absent: a NoData hole) has top -inf.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "core/geometry.hpp"
#include "core/terrain.hpp"
#include "engine/radar/radar_surface.hpp"

namespace cullcheck::radar {

struct GridCell {
  Box2 box;
  double top = -HUGE_VAL;
  std::uint32_t first = 0, count = 0;  // its triangles: TriangleGrid::triangles()[first, first + count)
};

class TriangleGrid {
 public:
  // cells_x x cells_y cells (each at least 1) over the terrain's plan extent (buildings must
  // stand inside it). The terrain (and buildings) must outlive the grid.
  TriangleGrid(const RadarSurface& surface, std::uint32_t cells_x, std::uint32_t cells_y);

  const Terrain& terrain() const { return surface_.terrain(); }
  const RadarSurface& surface() const { return surface_; }
  std::uint32_t cells_x() const { return cells_x_; }
  std::uint32_t cells_y() const { return cells_y_; }
  const Box2& plan() const { return plan_; }
  const GridCell& cell(std::uint32_t cx, std::uint32_t cy) const { return cells_[std::size_t(cy) * cells_x_ + cx]; }
  const std::vector<GridCell>& cells() const { return cells_; }
  std::span<const std::uint32_t> triangles_of(const GridCell& c) const { return {refs_.data() + c.first, c.count}; }
  // The cell holding plan point p, clamped onto the grid.
  std::uint32_t cell_index_at(Vec2 p) const;
  // Per triangle: highest and lowest vertex, and plan box.
  double top(std::uint32_t t) const { return top_[t]; }
  double bottom(std::uint32_t t) const { return bottom_[t]; }
  // Triangle references over all cells (a triangle meeting k cells counts k times).
  std::size_t references() const { return refs_.size(); }

 private:
  RadarSurface surface_;
  std::uint32_t cells_x_, cells_y_;
  Box2 plan_;
  double cell_w_, cell_h_;
  std::vector<GridCell> cells_;
  std::vector<std::uint32_t> refs_;
  std::vector<double> top_, bottom_;
};

}  // namespace cullcheck::radar
