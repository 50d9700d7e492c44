// Footprint shapes for the generated cities, in a local frame centred on the origin with width
// w along x and depth d along y, counter-clockwise, then rotated and placed on the 1 mm grid.
//
// Rotations avoid std::sin/std::cos: a direction is built from the half-angle tangent t as
// ((1 - t^2) / (1 + t^2), 2t / (1 + t^2)) plus whole quarter turns, which are exact. These are
// single IEEE operations, so a seed rotates a footprint identically on every machine.
#pragma once

#include <vector>

#include "core/geometry.hpp"
#include "generators/grid_snap.hpp"

namespace cullcheck::generators {

using Ring = std::vector<Vec2>;

struct PlanarRotation {
  double cos = 1.0;
  double sin = 0.0;
};

// t in [-1, 1] covers (-90, 90) degrees; quarter_turns adds k * 90 degrees exactly.
PlanarRotation rotation_from_half_tangent(double t, int quarter_turns = 0);
Vec2 rotate(Vec2 p, PlanarRotation r);

// Rotates the local ring, moves it to `centre` and rounds every vertex to whole millimetres.
Ring place_on_grid(const Ring& local, PlanarRotation r, Vec2 centre);

Box2 bounds_of(const Ring& ring);

Ring rectangle_ring(double w, double d);
// Rectangle with its top-right corner cut away: a vertical arm of width arm_w on the left and a
// horizontal arm of depth arm_d along the bottom.
Ring l_shape_ring(double w, double d, double arm_w, double arm_d);
// Rectangle with a notch cut from the middle of its top side: two arms of width arm_w standing
// on a base of depth base_d.
Ring u_shape_ring(double w, double d, double arm_w, double base_d);
// A bar of depth bar_d along the top, on a centred stem of width stem_w.
Ring t_shape_ring(double w, double d, double stem_w, double bar_d);
// Vertices on the ellipse with axes w and d, at increasing positions u in [0, 4) (quadrant
// index plus a fraction). Points on an ellipse are always in convex position, so the ring is
// convex without a hull computation.
Ring ellipse_ring(double w, double d, const std::vector<double>& positions);

// The thesis test city's building (ch. 3.2: 46 triangles = 3n - 2 for n = 16): a rectangle
// [lo, hi] in whole millimetres whose four corners are rounded by four vertices each, placed
// on a circle of radius `radius_mm` at the Pythagorean directions (1, 0), (4/5, 3/5),
// (3/5, 4/5), (0, 1), so the corner shape needs no trigonometry. Strictly convex.
Ring rounded_rectangle16(Millimetres lo_x, Millimetres lo_y, Millimetres hi_x, Millimetres hi_y, Millimetres radius_mm);

}  // namespace cullcheck::generators
