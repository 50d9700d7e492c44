// A uniform grid of axis-aligned boxes in the plan view.
//
// Two uses: (1) rejection placement without overlaps - a candidate footprint's box, grown by
// the minimum gap, is accepted only if it meets no box already placed (a box test is
// conservative: footprints lie inside their boxes, so disjoint boxes mean disjoint footprints);
// (2) a spatial index of a scene's buildings for point queries (is this camera in the open?).
// Cells are fixed at construction; boxes outside the covered area are clamped to border cells,
// so queries stay correct everywhere, only slower far outside.
#pragma once

#include <cstdint>
#include <vector>

#include "core/geometry.hpp"

namespace cullcheck::generators {

class BoxGrid {
 public:
  // Covers `area` with square cells of side >= cell_size (fewer cells if the count would exceed
  // max_cells per axis).
  BoxGrid(const Box2& area, double cell_size, int max_cells_per_axis = 1024);

  // Stores `box` under `index` in every cell it touches.
  void insert(const Box2& box, std::uint32_t index);
  // True if some stored box intersects `box` (closed boxes: touching counts).
  bool any_intersects(const Box2& box) const;
  // Indices of stored boxes that touch `box`, each once, in increasing order.
  std::vector<std::uint32_t> query(const Box2& box) const;

  const std::vector<Box2>& boxes() const { return boxes_; }

 private:
  struct CellRange {
    int x0, y0, x1, y1;
  };
  CellRange cells_of(const Box2& box) const;

  Box2 area_;
  double cell_ = 1.0;
  int nx_ = 1, ny_ = 1;
  std::vector<std::vector<std::uint32_t>> cells_;  // entries index into boxes_/ids_
  std::vector<Box2> boxes_;
  std::vector<std::uint32_t> ids_;
};

inline bool boxes_intersect(const Box2& a, const Box2& b) {
  return a.lo.x <= b.hi.x && b.lo.x <= a.hi.x && a.lo.y <= b.hi.y && b.lo.y <= a.hi.y;
}
inline Box2 grown(const Box2& b, double by) { return {{b.lo.x - by, b.lo.y - by}, {b.hi.x + by, b.hi.y + by}}; }

}  // namespace cullcheck::generators
