#include "generators/manhattan_layout.hpp"

#include <algorithm>
#include <cmath>

namespace cullcheck::generators {
namespace {

int rows_for(int n) {
  int r = static_cast<int>(std::sqrt(static_cast<double>(n)));
  while (r * r > n) --r;
  while ((r + 1) * (r + 1) <= n) ++r;
  return std::max(r, 1);
}

}  // namespace

MillimetreBox ManhattanLayout::block_box(int i, int j) const {
  const Millimetres x = origin_x + street + i * pitch, y = origin_y + street + j * pitch;
  return {x, y, x + block, y + block};
}

double ManhattanLayout::street_x(int k) const { return metres(origin_x + k * pitch) + metres(street) / 2; }
double ManhattanLayout::street_y(int k) const { return metres(origin_y + k * pitch) + metres(street) / 2; }

Box2 ManhattanLayout::extent() const {
  return {{metres(origin_x), metres(origin_y)},
          {metres(origin_x + blocks_x * pitch + street), metres(origin_y + blocks_y * pitch + street)}};
}

ManhattanLayout manhattan_layout(const ManhattanParams& p) {
  ManhattanLayout l;
  l.blocks_x = p.blocks_x, l.blocks_y = p.blocks_y;
  l.block = to_mm(p.block_size), l.street = to_mm(p.street_width), l.pitch = l.block + l.street;
  l.origin_x = -((p.blocks_x * l.pitch + l.street) / 2);
  l.origin_y = -((p.blocks_y * l.pitch + l.street) / 2);
  // The plaza sits in the middle; with an odd remainder it leans towards low indices.
  l.plaza_x0 = (p.blocks_x - p.plaza_blocks_x) / 2, l.plaza_x1 = l.plaza_x0 + p.plaza_blocks_x;
  l.plaza_y0 = (p.blocks_y - p.plaza_blocks_y) / 2, l.plaza_y1 = l.plaza_y0 + p.plaza_blocks_y;
  return l;
}

std::vector<MillimetreBox> lots_of_block(const MillimetreBox& b, int n) {
  const int rows = rows_for(n);
  const Millimetres depth = b.hi_y - b.lo_y, width = b.hi_x - b.lo_x;
  std::vector<MillimetreBox> lots;
  lots.reserve(n);
  for (int r = 0; r < rows; ++r) {
    const int cols = n / rows + (r < n % rows ? 1 : 0);
    const Millimetres y0 = b.lo_y + depth * r / rows, y1 = b.lo_y + depth * (r + 1) / rows;
    for (int c = 0; c < cols; ++c)
      lots.push_back({b.lo_x + width * c / cols, y0, b.lo_x + width * (c + 1) / cols, y1});
  }
  return lots;
}

Millimetres narrowest_lot_side(Millimetres block, int n) {
  const int rows = rows_for(n);
  const int most_cols = n / rows + (n % rows ? 1 : 0);
  return block / std::max(rows, most_cols);  // integer division floors, as in lots_of_block
}

}  // namespace cullcheck::generators
