// Geometry of a Manhattan grid from its parameters, in whole millimetres: block rectangles,
// lots inside a block, street centre lines, the plaza. The city generator places buildings
// with it and the street walk follows its streets, so the two always agree.
//
// Along x (y alike): street, block 0, street, block 1, ..., block n-1, street. The city is
// centred on the origin; street k's centre line (k = 0..n) lies between block k-1 and block k.
#pragma once

#include <algorithm>
#include <vector>

#include "core/geometry.hpp"
#include "generators/city.hpp"
#include "generators/grid_snap.hpp"
#include "generators/random.hpp"

namespace cullcheck::generators {

struct MillimetreBox {
  Millimetres lo_x = 0, lo_y = 0, hi_x = 0, hi_y = 0;
};

// A length drawn uniformly in whole millimetres: between two lengths in metres, or between two
// lengths in millimetres (the upper one raised to the lower where it falls below).
inline Millimetres draw_mm(Random& rng, double lo, double hi) { return rng.uniform_int(to_mm(lo), to_mm(hi)); }
inline Millimetres draw_mm(Random& rng, Millimetres lo, Millimetres hi) { return rng.uniform_int(lo, std::max(lo, hi)); }

struct ManhattanLayout {
  int blocks_x = 0, blocks_y = 0;
  Millimetres block = 0, street = 0, pitch = 0;  // pitch = block + street
  Millimetres origin_x = 0, origin_y = 0;        // low corner of the whole city (outer street edge)
  int plaza_x0 = 0, plaza_x1 = 0, plaza_y0 = 0, plaza_y1 = 0;  // emptied blocks [x0, x1) x [y0, y1)

  MillimetreBox block_box(int i, int j) const;
  bool is_plaza_block(int i, int j) const { return i >= plaza_x0 && i < plaza_x1 && j >= plaza_y0 && j < plaza_y1; }
  // Centre lines of the streets running north-south (x = const, k = 0..blocks_x) and
  // east-west (y = const, k = 0..blocks_y), in metres.
  double street_x(int k) const;
  double street_y(int k) const;
  double street_width() const { return metres(street); }
  // The whole city including the outer streets, in metres.
  Box2 extent() const;
};

// Assumes validate(p) passed.
ManhattanLayout manhattan_layout(const ManhattanParams& p);

// Splits a block into n lots: r = floor(sqrt(n)) rows along y; the first n mod r rows hold one
// lot more than the others (n / r); lots in a row share the row's width equally. Lot edges are
// whole millimetres and tile the block exactly.
std::vector<MillimetreBox> lots_of_block(const MillimetreBox& block, int n);
// The narrowest lot side that lots_of_block gives for a block of side `block` and n lots.
Millimetres narrowest_lot_side(Millimetres block, int n);

}  // namespace cullcheck::generators
