#include "engine/radar/triangle_grid.hpp"

#include <algorithm>
#include <stdexcept>

namespace cullcheck::radar {
namespace {

// Whether the segment pq meets the closed box (Liang-Barsky clipping).
bool segment_meets(Vec2 p, Vec2 q, const Box2& b) {
  double t0 = 0.0, t1 = 1.0;
  const Vec2 d = q - p;
  const double ps[4] = {-d.x, d.x, -d.y, d.y}, qs[4] = {p.x - b.lo.x, b.hi.x - p.x, p.y - b.lo.y, b.hi.y - p.y};
  for (int k = 0; k < 4; ++k) {
    if (ps[k] == 0.0) {
      if (qs[k] < 0.0) return false;
      continue;
    }
    const double r = qs[k] / ps[k];
    if (ps[k] < 0.0) t0 = std::max(t0, r);
    else t1 = std::min(t1, r);
    if (t0 > t1) return false;
  }
  return true;
}

// Whether the plan triangle abc (counter-clockwise) and the box overlap with positive area:
// neither the box's axes nor the triangle's edge normals separate them (touching separates).
// A triangle standing on edge (a building's wall: its plan is a segment) is in every cell its
// segment meets, touching included.
bool overlaps(const Vec2 (&v)[3], const Box2& b) {
  if (cross(v[1] - v[0], v[2] - v[0]) == 0.0) {
    Vec2 lo = v[0], hi = v[0];  // the segment's ends: the extreme points along it
    const Vec2 d = (v[1] - v[0]) + (v[2] - v[0]);
    for (const Vec2& p : v) {
      if (dot(p - lo, d) < 0.0) lo = p;
      if (dot(p - hi, d) > 0.0) hi = p;
    }
    return segment_meets(lo, hi, b);
  }
  const double lo_x = std::min({v[0].x, v[1].x, v[2].x}), hi_x = std::max({v[0].x, v[1].x, v[2].x});
  const double lo_y = std::min({v[0].y, v[1].y, v[2].y}), hi_y = std::max({v[0].y, v[1].y, v[2].y});
  if (hi_x <= b.lo.x || lo_x >= b.hi.x || hi_y <= b.lo.y || lo_y >= b.hi.y) return false;
  const Vec2 corners[4] = {b.lo, {b.hi.x, b.lo.y}, b.hi, {b.lo.x, b.hi.y}};
  for (int e = 0; e < 3; ++e) {
    const Vec2 a = v[e], c = v[(e + 1) % 3];
    // The box lies wholly on or beyond the edge's outer side.
    bool all_outside = true;
    for (const Vec2& k : corners) all_outside = all_outside && cross(c - a, k - a) <= 0.0;
    if (all_outside) return false;
  }
  return true;
}

}  // namespace

TriangleGrid::TriangleGrid(const RadarSurface& surface, std::uint32_t cells_x, std::uint32_t cells_y)
    : surface_(surface), cells_x_(cells_x), cells_y_(cells_y) {
  const Terrain& terrain = surface.terrain();
  if (cells_x == 0 || cells_y == 0) throw std::invalid_argument("TriangleGrid: a grid needs at least 1 x 1 cells");
  const Box3 b = terrain.bounds();
  plan_ = b.plan();
  cell_w_ = (plan_.hi.x - plan_.lo.x) / cells_x;
  cell_h_ = (plan_.hi.y - plan_.lo.y) / cells_y;
  cells_.resize(std::size_t(cells_x) * cells_y);
  for (std::uint32_t cy = 0; cy < cells_y; ++cy)
    for (std::uint32_t cx = 0; cx < cells_x; ++cx) {
      GridCell& c = cells_[std::size_t(cy) * cells_x + cx];
      // The last row and column end exactly on the plan's edge.
      c.box.lo = {plan_.lo.x + cx * cell_w_, plan_.lo.y + cy * cell_h_};
      c.box.hi = {cx + 1 == cells_x ? plan_.hi.x : plan_.lo.x + (cx + 1) * cell_w_,
                  cy + 1 == cells_y ? plan_.hi.y : plan_.lo.y + (cy + 1) * cell_h_};
    }
  const std::size_t n = surface.triangle_count();
  top_.assign(n, -HUGE_VAL);
  bottom_.assign(n, HUGE_VAL);
  // Two passes: count each cell's triangles, then place them; a triangle's candidate cells are
  // those its plan box overlaps.
  std::vector<std::uint32_t> counts(cells_.size(), 0);
  const auto for_each_cell = [&](std::size_t t, auto&& f) {
    const auto p = surface_.triangle(t);
    const Vec2 v[3] = {cullcheck::plan(p[0]), cullcheck::plan(p[1]), cullcheck::plan(p[2])};
    const double lo_x = std::min({v[0].x, v[1].x, v[2].x}), hi_x = std::max({v[0].x, v[1].x, v[2].x});
    const double lo_y = std::min({v[0].y, v[1].y, v[2].y}), hi_y = std::max({v[0].y, v[1].y, v[2].y});
    const auto clamp_x = [&](double x) { return std::uint32_t(std::clamp((x - plan_.lo.x) / cell_w_, 0.0, double(cells_x_ - 1))); };
    const auto clamp_y = [&](double y) { return std::uint32_t(std::clamp((y - plan_.lo.y) / cell_h_, 0.0, double(cells_y_ - 1))); };
    // One cell of margin each way: the division may round a box edge into the neighbour.
    const std::uint32_t x0 = clamp_x(lo_x) > 0 ? clamp_x(lo_x) - 1 : 0, x1 = std::min(clamp_x(hi_x) + 1, cells_x_ - 1);
    const std::uint32_t y0 = clamp_y(lo_y) > 0 ? clamp_y(lo_y) - 1 : 0, y1 = std::min(clamp_y(hi_y) + 1, cells_y_ - 1);
    for (std::uint32_t cy = y0; cy <= y1; ++cy)
      for (std::uint32_t cx = x0; cx <= x1; ++cx) {
        const std::size_t c = std::size_t(cy) * cells_x_ + cx;
        if (overlaps(v, cells_[c].box)) f(c);
      }
  };
  for (std::size_t t = 0; t < n; ++t) {
    if (!surface_.present(t)) continue;
    const auto p = surface_.triangle(t);
    top_[t] = std::max({p[0].z, p[1].z, p[2].z});
    bottom_[t] = std::min({p[0].z, p[1].z, p[2].z});
    for_each_cell(t, [&](std::size_t c) { ++counts[c]; });
  }
  std::uint32_t next = 0;
  for (std::size_t c = 0; c < cells_.size(); ++c) {
    cells_[c].first = next;
    next += counts[c];
    counts[c] = 0;
  }
  refs_.resize(next);
  for (std::size_t t = 0; t < n; ++t) {
    if (!surface_.present(t)) continue;
    for_each_cell(t, [&](std::size_t c) { refs_[cells_[c].first + counts[c]++] = std::uint32_t(t); });
  }
  for (GridCell& c : cells_) {
    c.count = counts[&c - cells_.data()];
    const auto first = refs_.begin() + c.first, last = first + c.count;
    // Highest first; ties by number, so the order is the same everywhere.
    std::sort(first, last, [&](std::uint32_t a, std::uint32_t b) { return top_[a] != top_[b] ? top_[a] > top_[b] : a < b; });
    if (c.count > 0) c.top = top_[*first];
  }
}

std::uint32_t TriangleGrid::cell_index_at(Vec2 p) const {
  const auto cx = std::uint32_t(std::clamp((p.x - plan_.lo.x) / cell_w_, 0.0, double(cells_x_ - 1)));
  const auto cy = std::uint32_t(std::clamp((p.y - plan_.lo.y) / cell_h_, 0.0, double(cells_y_ - 1)));
  return cy * cells_x_ + cx;
}

}  // namespace cullcheck::radar
