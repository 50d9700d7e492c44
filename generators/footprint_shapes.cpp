#include "generators/footprint_shapes.hpp"

#include <cmath>

namespace cullcheck::generators {

PlanarRotation rotation_from_half_tangent(double t, int quarter_turns) {
  const double tt = t * t;
  PlanarRotation r{(1.0 - tt) / (1.0 + tt), (2.0 * t) / (1.0 + tt)};
  for (int k = ((quarter_turns % 4) + 4) % 4; k > 0; --k) r = {-r.sin, r.cos};
  return r;
}

Vec2 rotate(Vec2 p, PlanarRotation r) { return {r.cos * p.x - r.sin * p.y, r.sin * p.x + r.cos * p.y}; }

Ring place_on_grid(const Ring& local, PlanarRotation r, Vec2 centre) {
  Ring out;
  out.reserve(local.size());
  for (Vec2 p : local) out.push_back(snap_mm(rotate(p, r) + centre));
  return out;
}

Box2 bounds_of(const Ring& ring) {
  Box2 box;
  for (Vec2 p : ring) box.extend(p);
  return box;
}

Ring rectangle_ring(double w, double d) {
  const double x = w / 2, y = d / 2;
  return {{-x, -y}, {x, -y}, {x, y}, {-x, y}};
}

Ring l_shape_ring(double w, double d, double arm_w, double arm_d) {
  const double x0 = -w / 2, x1 = w / 2, y0 = -d / 2, y1 = d / 2;
  return {{x0, y0}, {x1, y0}, {x1, y0 + arm_d}, {x0 + arm_w, y0 + arm_d}, {x0 + arm_w, y1}, {x0, y1}};
}

Ring u_shape_ring(double w, double d, double arm_w, double base_d) {
  const double x0 = -w / 2, x1 = w / 2, y0 = -d / 2, y1 = d / 2;
  return {{x0, y0},         {x1, y0},         {x1, y1}, {x1 - arm_w, y1}, {x1 - arm_w, y0 + base_d},
          {x0 + arm_w, y0 + base_d}, {x0 + arm_w, y1}, {x0, y1}};
}

Ring t_shape_ring(double w, double d, double stem_w, double bar_d) {
  const double x0 = -w / 2, x1 = w / 2, y0 = -d / 2, y1 = d / 2, s = stem_w / 2;
  return {{-s, y0}, {s, y0}, {s, y1 - bar_d}, {x1, y1 - bar_d}, {x1, y1}, {x0, y1}, {x0, y1 - bar_d}, {-s, y1 - bar_d}};
}

Ring ellipse_ring(double w, double d, const std::vector<double>& positions) {
  // Inside one quadrant the half-angle tangent runs over [-tan(pi/8), tan(pi/8)], i.e. the
  // directions within 45 degrees of that quadrant's axis; quadrant k is turned by k * 90 degrees.
  constexpr double kTanPiOver8 = 0.41421356237309503;
  Ring ring;
  ring.reserve(positions.size());
  for (double u : positions) {
    const int quadrant = static_cast<int>(std::floor(u));
    const double t = (2.0 * (u - quadrant) - 1.0) * kTanPiOver8;
    const PlanarRotation dir = rotation_from_half_tangent(t, quadrant);
    ring.push_back({dir.cos * (w / 2), dir.sin * (d / 2)});
  }
  return ring;
}

Ring rounded_rectangle16(Millimetres lo_x, Millimetres lo_y, Millimetres hi_x, Millimetres hi_y, Millimetres radius_mm) {
  // Unit directions for the bottom-right corner (-90 .. 0 degrees), in tenths: exact integers.
  constexpr int kDirs[4][2] = {{0, -10}, {6, -8}, {8, -6}, {10, 0}};
  const Millimetres centres[4][2] = {{hi_x - radius_mm, lo_y + radius_mm},
                                     {hi_x - radius_mm, hi_y - radius_mm},
                                     {lo_x + radius_mm, hi_y - radius_mm},
                                     {lo_x + radius_mm, lo_y + radius_mm}};
  Ring ring;
  ring.reserve(16);
  for (int corner = 0; corner < 4; ++corner) {
    for (const auto& dir : kDirs) {
      long long dx = dir[0], dy = dir[1];
      for (int k = 0; k < corner; ++k) {  // quarter turn (x, y) -> (-y, x)
        const long long t = dx;
        dx = -dy, dy = t;
      }
      // Round half away from zero in integer arithmetic: radius * dir / 10.
      auto scaled = [&](long long v) {
        const long long num = radius_mm * v;
        return num >= 0 ? (num + 5) / 10 : -((-num + 5) / 10);
      };
      ring.push_back({metres(centres[corner][0] + scaled(dx)), metres(centres[corner][1] + scaled(dy))});
    }
  }
  return ring;
}

}  // namespace cullcheck::generators
