#include "generators/box_grid.hpp"

#include <algorithm>
#include <cmath>

namespace cullcheck::generators {

BoxGrid::BoxGrid(const Box2& area, double cell_size, int max_cells_per_axis) : area_(area) {
  if (area_.empty()) area_ = {{0, 0}, {1, 1}};
  const double span = std::max({area_.hi.x - area_.lo.x, area_.hi.y - area_.lo.y, 1e-3});
  cell_ = std::max({cell_size, span / max_cells_per_axis, 1e-3});
  nx_ = std::clamp(static_cast<int>(std::ceil((area_.hi.x - area_.lo.x) / cell_)), 1, max_cells_per_axis);
  ny_ = std::clamp(static_cast<int>(std::ceil((area_.hi.y - area_.lo.y) / cell_)), 1, max_cells_per_axis);
  cells_.resize(static_cast<std::size_t>(nx_) * ny_);
}

BoxGrid::CellRange BoxGrid::cells_of(const Box2& b) const {
  auto cx = [&](double x) { return std::clamp(static_cast<int>(std::floor((x - area_.lo.x) / cell_)), 0, nx_ - 1); };
  auto cy = [&](double y) { return std::clamp(static_cast<int>(std::floor((y - area_.lo.y) / cell_)), 0, ny_ - 1); };
  return {cx(b.lo.x), cy(b.lo.y), cx(b.hi.x), cy(b.hi.y)};
}

void BoxGrid::insert(const Box2& box, std::uint32_t index) {
  const auto slot = static_cast<std::uint32_t>(boxes_.size());
  boxes_.push_back(box);
  ids_.push_back(index);
  const CellRange r = cells_of(box);
  for (int y = r.y0; y <= r.y1; ++y)
    for (int x = r.x0; x <= r.x1; ++x) cells_[static_cast<std::size_t>(y) * nx_ + x].push_back(slot);
}

bool BoxGrid::any_intersects(const Box2& box) const {
  const CellRange r = cells_of(box);
  for (int y = r.y0; y <= r.y1; ++y)
    for (int x = r.x0; x <= r.x1; ++x)
      for (std::uint32_t slot : cells_[static_cast<std::size_t>(y) * nx_ + x])
        if (boxes_intersect(boxes_[slot], box)) return true;
  return false;
}

std::vector<std::uint32_t> BoxGrid::query(const Box2& box) const {
  std::vector<std::uint32_t> out;
  const CellRange r = cells_of(box);
  for (int y = r.y0; y <= r.y1; ++y)
    for (int x = r.x0; x <= r.x1; ++x)
      for (std::uint32_t slot : cells_[static_cast<std::size_t>(y) * nx_ + x])
        if (boxes_intersect(boxes_[slot], box)) out.push_back(ids_[slot]);
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

}  // namespace cullcheck::generators
