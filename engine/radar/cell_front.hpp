// The radar sweep's order (thesis ch. 3.3.2, step 2): the cells of a TriangleGrid met from
// front to back around a plan point, best-first on their nearest plan distance, flooding from
// the point's cell to its four neighbours. Since a cell's nearest distance is never below its
// flooding neighbour's, every cell the caller admits is met in order of distance, hidden or not.
#pragma once

#include <algorithm>
#include <cstdint>
#include <functional>
#include <queue>
#include <utility>
#include <vector>

#include "core/geometry.hpp"
#include "engine/radar/triangle_grid.hpp"

namespace cullcheck::radar {

class CellFront {
 public:
  explicit CellFront(const TriangleGrid& grid) : grid_(grid), queued_(grid.cells().size(), 0) {}

  // Starts a sweep from the cell holding plan point e.
  void start(Vec2 e) {
    if (++stamp_ == 0) {  // the stamps wrapped: start them over
      std::fill(queued_.begin(), queued_.end(), 0);
      stamp_ = 1;
    }
    e_ = e;
    front_ = {};
    const std::uint32_t first = grid_.cell_index_at(e);
    front_.push({0.0, first});
    queued_[first] = stamp_;
  }
  bool empty() const { return front_.empty(); }
  // The nearest cell not yet met (its nearest plan distance and index); its neighbours that
  // `admit(const GridCell&)` accepts join the front.
  template <class Admit>
  std::pair<double, std::uint32_t> next(Admit&& admit) {
    const auto top = front_.top();
    front_.pop();
    const std::uint32_t nx = grid_.cells_x(), ny = grid_.cells_y();
    const std::uint32_t cx = top.second % nx, cy = top.second / nx;
    const auto flood = [&](std::uint32_t x, std::uint32_t y) {
      const std::uint32_t n = y * nx + x;
      if (queued_[n] == stamp_ || !admit(grid_.cells()[n])) return;
      queued_[n] = stamp_;
      front_.push({min_distance(e_, grid_.cells()[n].box), n});
    };
    if (cx > 0) flood(cx - 1, cy);
    if (cx + 1 < nx) flood(cx + 1, cy);
    if (cy > 0) flood(cx, cy - 1);
    if (cy + 1 < ny) flood(cx, cy + 1);
    return top;
  }

 private:
  using Entry = std::pair<double, std::uint32_t>;  // nearest plan distance, cell index
  const TriangleGrid& grid_;
  std::vector<std::uint32_t> queued_;  // per cell: the sweep that queued it
  std::uint32_t stamp_ = 0;
  Vec2 e_{};
  std::priority_queue<Entry, std::vector<Entry>, std::greater<>> front_;
};

}  // namespace cullcheck::radar
