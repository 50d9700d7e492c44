#include "engine/polar_diagram/visibility_fan.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "engine/polar_diagram/exact_sign.hpp"

namespace cullcheck::polar {
namespace {

constexpr Vec2 kAxes[4] = {{1.0, 0.0}, {0.0, 1.0}, {-1.0, 0.0}, {0.0, -1.0}};  // E, N, W, S

double approx_cross(Vec2 a, Vec2 b) { return a.x * b.y - a.y * b.x; }

}  // namespace

PlanWedge plan_wedge(const Camera& camera) {
  PlanWedge w;
  if (camera.omnidirectional()) return w;
  w.everything = false;
  const double r = camera.yaw - camera.hfov / 2, l = camera.yaw + camera.hfov / 2;
  w.right = {std::cos(r), std::sin(r)};
  w.left = {std::cos(l), std::sin(l)};
  return w;
}

// Per-query marks, kept between queries so that a query touches only what it visits (never
// O(n) clearing): a mark is current when it equals the query's or the ray's stamp.
struct VisibilityFan::Scratch {
  std::vector<std::uint32_t> edge_stamp, object_query, edge_query;
  std::uint32_t stamp = 0, query = 0;
};

namespace {
// A cell index clamped in double first: a far or infinite coordinate must not overflow the cast.
int clamped_cell(double at, double origin, double cell, int n) {
  const double v = std::floor((at - origin) / cell);
  if (!(v >= 0)) return 0;  // also NaN
  return v >= n - 1 ? n - 1 : static_cast<int>(v);
}
}  // namespace

int VisibilityFan::Grid::cx(double x) const { return clamped_cell(x, origin.x, cell, nx); }
int VisibilityFan::Grid::cy(double y) const { return clamped_cell(y, origin.y, cell, ny); }

VisibilityFan::VisibilityFan(const Scene& scene, FanOptions options)
    : options_(options), points_(footprint_vertices(scene)), diagrams_(points_) {
  building_vertices_ = points_.size();  // the frame's corners follow, outside the diagrams
  Box2 bounds;
  for (std::uint32_t i = 0; i < scene.buildings.size(); ++i) {
    const Building& b = scene.buildings[i];
    ids_.push_back(b.id);
    const auto first = static_cast<std::uint32_t>(point_object_.size());
    const auto n = static_cast<std::uint32_t>(b.footprint.size());
    for (std::uint32_t k = 0; k < n; ++k) {
      point_object_.push_back(i);
      edges_.push_back({first + k, first + (k + 1) % n, i});
      bounds.extend(b.footprint[k]);
    }
  }
  // The frame closes every ray, so every shot meets something; it is no object.
  if (bounds.empty()) bounds.extend(Vec2{0.0, 0.0});
  const double margin = 10.0 + 0.25 * std::max(bounds.hi.x - bounds.lo.x, bounds.hi.y - bounds.lo.y);
  frame_ = {{bounds.lo.x - margin, bounds.lo.y - margin}, {bounds.hi.x + margin, bounds.hi.y + margin}};
  const auto corner0 = static_cast<std::uint32_t>(points_.size());
  for (Vec2 c : {frame_.lo, Vec2{frame_.hi.x, frame_.lo.y}, frame_.hi, Vec2{frame_.lo.x, frame_.hi.y}}) {
    points_.push_back(c);
    point_object_.push_back(kFrame);
  }
  for (std::uint32_t k = 0; k < 4; ++k) edges_.push_back({corner0 + k, corner0 + (k + 1) % 4, kFrame});

  // About two vertices per cell; the grid reaches a little beyond the frame so that the frame's
  // edges lie inside it.
  const double w = frame_.hi.x - frame_.lo.x, h = frame_.hi.y - frame_.lo.y;
  const double cells = std::clamp(static_cast<double>(points_.size()) / 2.0, 16.0, 4.0e6);
  grid_.cell = std::sqrt(w * h / cells);
  grid_.origin = {frame_.lo.x - grid_.cell, frame_.lo.y - grid_.cell};
  grid_.nx = static_cast<int>(std::ceil(w / grid_.cell)) + 2;
  grid_.ny = static_cast<int>(std::ceil(h / grid_.cell)) + 2;
  const std::size_t n_cells = static_cast<std::size_t>(grid_.nx) * static_cast<std::size_t>(grid_.ny);
  // Counting sort into compressed rows, edges by their padded bounding boxes.
  const double pad = 1e-7 * grid_.cell;
  auto edge_cells = [&](const Edge& e, auto&& visit) {
    const Vec2 a = points_[e.a], b = points_[e.b];
    const int x0 = grid_.cx(std::min(a.x, b.x) - pad), x1 = grid_.cx(std::max(a.x, b.x) + pad);
    const int y0 = grid_.cy(std::min(a.y, b.y) - pad), y1 = grid_.cy(std::max(a.y, b.y) + pad);
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x) visit(static_cast<std::size_t>(y) * grid_.nx + x);
  };
  grid_.edge_begin.assign(n_cells + 1, 0);
  for (const Edge& e : edges_) edge_cells(e, [&](std::size_t c) { ++grid_.edge_begin[c + 1]; });
  for (std::size_t c = 0; c < n_cells; ++c) grid_.edge_begin[c + 1] += grid_.edge_begin[c];
  grid_.edge_items.resize(grid_.edge_begin[n_cells]);
  {
    std::vector<std::uint32_t> fill(grid_.edge_begin.begin(), grid_.edge_begin.end() - 1);
    for (std::uint32_t i = 0; i < edges_.size(); ++i) edge_cells(edges_[i], [&](std::size_t c) { grid_.edge_items[fill[c]++] = i; });
  }
  grid_.vertex_begin.assign(n_cells + 1, 0);
  auto vertex_cell = [&](Vec2 v) { return static_cast<std::size_t>(grid_.cy(v.y)) * grid_.nx + grid_.cx(v.x); };
  for (Vec2 v : points_) ++grid_.vertex_begin[vertex_cell(v) + 1];
  for (std::size_t c = 0; c < n_cells; ++c) grid_.vertex_begin[c + 1] += grid_.vertex_begin[c];
  grid_.vertex_items.resize(points_.size());
  {
    std::vector<std::uint32_t> fill(grid_.vertex_begin.begin(), grid_.vertex_begin.end() - 1);
    for (std::uint32_t i = 0; i < points_.size(); ++i) grid_.vertex_items[fill[vertex_cell(points_[i])]++] = i;
  }
  scratch_ = std::make_unique<Scratch>();
  scratch_->edge_stamp.assign(edges_.size(), 0u);
  scratch_->object_query.assign(ids_.size(), 0u);
  scratch_->edge_query.assign(edges_.size(), 0u);
}

VisibilityFan::~VisibilityFan() = default;

int VisibilityFan::side(const Dir& d, Vec2 x, Vec2 eye, int sense) const { return sense * cross_sign(d.a, d.b, x, eye); }

// Whether edge e meets the ray just past direction d (turned by an infinitesimal in `sense`).
bool VisibilityFan::crosses_after(std::uint32_t e, const Dir& d, Vec2 eye, int sense) const {
  const Vec2 a = points_[edges_[e].a], b = points_[edges_[e].b];
  const int sa = side(d, a, eye, sense), sb = side(d, b, eye, sense);
  if (sa == sb) return false;          // both on one side, or seen edge-on along the ray
  if (sa < 0 && sb > 0) return sense * orient(eye, a, b) > 0;  // crosses the ray in front of the eye
  if (sa > 0 && sb < 0) return sense * orient(eye, b, a) > 0;
  if (sa == 0 && sb > 0) return dot_sign(d.a, d.b, a, eye) > 0;  // leaves the ray from a point in front
  if (sb == 0 && sa > 0) return dot_sign(d.a, d.b, b, eye) > 0;
  return false;
}

// Whether e1 lies nearer the eye than e2 along every ray meeting both (edges of footprints that
// do not overlap cross nowhere inside such a ray's wedge, so one line separates them).
bool VisibilityFan::nearer(std::uint32_t e1, std::uint32_t e2, Vec2 eye) const {
  const Vec2 a1 = points_[edges_[e1].a], b1 = points_[edges_[e1].b];
  const Vec2 a2 = points_[edges_[e2].a], b2 = points_[edges_[e2].b];
  const int s1 = orient(a1, b1, eye);
  const int o1 = orient(a1, b1, a2) * s1, o2 = orient(a1, b1, b2) * s1;
  if (o1 >= 0 && o2 >= 0 && (o1 | o2) != 0) return false;  // e2 on the eye's side of e1's line
  if (o1 <= 0 && o2 <= 0 && (o1 | o2) != 0) return true;
  if (o1 == 0 && o2 == 0) return e1 < e2;                 // collinear: inside a shared wall, never first
  const int s2 = orient(a2, b2, eye);
  const int q1 = orient(a2, b2, a1) * s2, q2 = orient(a2, b2, b1) * s2;
  return q1 >= 0 && q2 >= 0;
}

std::uint32_t VisibilityFan::far_end(std::uint32_t e, const Dir& d, Vec2 eye, int sense) const {
  return side(d, points_[edges_[e].b], eye, sense) > 0 ? edges_[e].b : edges_[e].a;
}

// The first edge met by the ray just past d: a grid walk from the eye's cell (Amanatides and
// Woo), every edge in a walked cell tested exactly, stopping once the nearest found lies before
// the walked cell's exit.
std::uint32_t VisibilityFan::shoot(Vec2 eye, const Dir& d, int sense, Scratch& s, FanResult& out) const {
  ++out.stats.rays;
  const Vec2 dir = d.a - d.b;
  int x = grid_.cx(eye.x), y = grid_.cy(eye.y);
  const int step_x = dir.x > 0 ? 1 : -1, step_y = dir.y > 0 ? 1 : -1;
  const double inf = std::numeric_limits<double>::infinity();
  auto boundary_t = [&](double from, double origin, int c, int step, double delta) {
    if (delta == 0) return inf;
    const double edge = origin + (c + (step > 0 ? 1 : 0)) * grid_.cell;
    return (edge - from) / delta;
  };
  double t_x = boundary_t(eye.x, grid_.origin.x, x, step_x, dir.x);
  double t_y = boundary_t(eye.y, grid_.origin.y, y, step_y, dir.y);
  const double dt_x = dir.x == 0 ? inf : grid_.cell / std::abs(dir.x);
  const double dt_y = dir.y == 0 ? inf : grid_.cell / std::abs(dir.y);
  std::int64_t best = -1;
  double best_t = inf;
  if (++s.stamp == 0) {
    std::fill(s.edge_stamp.begin(), s.edge_stamp.end(), 0u);
    s.stamp = 1;
  }
  while (x >= 0 && y >= 0 && x < grid_.nx && y < grid_.ny) {
    ++out.stats.cells_walked;
    const std::size_t c = static_cast<std::size_t>(y) * grid_.nx + x;
    for (std::uint32_t k = grid_.edge_begin[c]; k < grid_.edge_begin[c + 1]; ++k) {
      const std::uint32_t e = grid_.edge_items[k];
      if (s.edge_stamp[e] == s.stamp) continue;
      s.edge_stamp[e] = s.stamp;
      ++out.stats.edges_tested;
      if (!crosses_after(e, d, eye, sense)) continue;
      if (best >= 0 && !nearer(e, static_cast<std::uint32_t>(best), eye)) continue;
      best = e;
      // Where along the ray (in units of dir) it is met, in double: only to stop the walk.
      const Vec2 a = points_[edges_[e].a], b = points_[edges_[e].b];
      const double den = approx_cross(dir, b - a);
      best_t = den != 0 ? approx_cross(a - eye, b - a) / den
                        : std::min(std::abs(a.x - eye.x) + std::abs(a.y - eye.y), std::abs(b.x - eye.x) + std::abs(b.y - eye.y)) /
                              std::max(std::abs(dir.x), std::abs(dir.y));
    }
    const double exit = std::min(t_x, t_y);
    if (best >= 0 && best_t < exit * (1 - 1e-9)) return static_cast<std::uint32_t>(best);
    if (t_x < t_y) {
      x += step_x;
      t_x += dt_x;
    } else {
      y += step_y;
      t_y += dt_y;
    }
  }
  if (best >= 0) return static_cast<std::uint32_t>(best);
  throw std::logic_error("polar fan: a ray left the frame without meeting it (is the eye inside the frame?)");
}

// The angularly first vertex strictly inside the wedge from `cur` to the far end of `hit`, on
// the eye's side of (or on) hit's line: what stands in front of hit there. -1 when none.
std::int64_t VisibilityFan::first_in_front(Vec2 eye, const Dir& cur, std::uint32_t hit, std::uint32_t end, int sense,
                                           FanResult& out) const {
  const Vec2 a = points_[edges_[hit].a], b = points_[edges_[hit].b], w = points_[end];
  const int eye_side = orient(a, b, eye);
  // The triangle eye, hit point, w in double, to choose the cells; every vertex in them is tested
  // exactly, and the cells are padded by one on every side.
  const Vec2 dir = cur.a - cur.b;
  const double den = approx_cross(dir, b - a);
  Vec2 hit_point = w;
  if (den != 0) {
    const double t = approx_cross(a - eye, b - a) / den;
    if (std::isfinite(t) && t > 0) hit_point = eye + dir * t;
  }
  const Vec2 tri[3] = {eye, hit_point, w};
  double ylo = tri[0].y, yhi = tri[0].y;
  for (Vec2 v : tri) ylo = std::min(ylo, v.y), yhi = std::max(yhi, v.y);
  const int row0 = std::max(0, grid_.cy(ylo) - 1), row1 = std::min(grid_.ny - 1, grid_.cy(yhi) + 1);
  std::int64_t best = -1;
  for (int row = row0; row <= row1; ++row) {
    // The triangle's x-extent over this row's strip (widened by a cell above and below).
    const double y0 = grid_.origin.y + (row - 1) * grid_.cell, y1 = grid_.origin.y + (row + 2) * grid_.cell;
    double xlo = std::numeric_limits<double>::infinity(), xhi = -xlo;
    for (int i = 0; i < 3; ++i) {
      const Vec2 p = tri[i], q = tri[(i + 1) % 3];
      if (p.y >= y0 && p.y <= y1) xlo = std::min(xlo, p.x), xhi = std::max(xhi, p.x);
      for (double yy : {y0, y1}) {
        if ((p.y - yy) * (q.y - yy) > 0 || p.y == q.y) continue;
        const double xx = p.x + (q.x - p.x) * (yy - p.y) / (q.y - p.y);
        xlo = std::min(xlo, xx), xhi = std::max(xhi, xx);
      }
    }
    if (!(xlo <= xhi)) continue;
    const int col0 = std::max(0, grid_.cx(xlo) - 1), col1 = std::min(grid_.nx - 1, grid_.cx(xhi) + 1);
    for (int col = col0; col <= col1; ++col) {
      ++out.stats.cells_walked;
      const std::size_t c = static_cast<std::size_t>(row) * grid_.nx + col;
      for (std::uint32_t k = grid_.vertex_begin[c]; k < grid_.vertex_begin[c + 1]; ++k) {
        const std::uint32_t v = grid_.vertex_items[k];
        const Vec2 p = points_[v];
        ++out.stats.vertices_tested;
        if (side(cur, p, eye, sense) <= 0 || sense * orient(eye, w, p) >= 0) continue;  // outside the open wedge
        if (orient(a, b, p) * eye_side < 0) continue;                                 // behind hit's line
        if (best >= 0 && sense * orient(eye, points_[static_cast<std::size_t>(best)], p) >= 0) continue;  // not first
        best = v;
      }
    }
  }
  return best;
}

std::vector<VisibilityFan::Piece> VisibilityFan::pieces(const PlanWedge& wedge) const {
  const Vec2 zero{0.0, 0.0};
  using K = DiagramKind;
  std::vector<Piece> out;
  if (wedge.everything) {
    out.push_back({{kAxes[0], zero}, {kAxes[1], zero}, +1, static_cast<int>(K::east_plus)});
    out.push_back({{kAxes[2], zero}, {kAxes[1], zero}, -1, static_cast<int>(K::west_minus)});
    out.push_back({{kAxes[2], zero}, {kAxes[3], zero}, +1, static_cast<int>(K::west_plus)});
    out.push_back({{kAxes[0], zero}, {kAxes[3], zero}, -1, static_cast<int>(K::east_minus)});
    return out;
  }
  const Vec2 r = wedge.right, l = wedge.left;
  // Axes strictly inside the wedge (products with an axis are exact).
  const bool wide = approx_cross(r, l) < 0 || (approx_cross(r, l) == 0 && r.x * l.x + r.y * l.y < 0);
  std::vector<std::pair<double, int>> cuts;
  for (int k = 0; k < 4; ++k) {
    const Vec2 ax = kAxes[k];
    const double cr = approx_cross(r, ax), cl = approx_cross(ax, l);
    const bool inside = wide ? !(approx_cross(l, ax) >= 0 && approx_cross(ax, r) >= 0) : (cr > 0 && cl > 0);
    if (!inside || ax == r || ax == l) continue;
    double angle = std::atan2(cr, r.x * ax.x + r.y * ax.y);
    if (angle <= 0) angle += 2 * M_PI;
    cuts.push_back({angle, k});
  }
  std::sort(cuts.begin(), cuts.end());
  std::vector<Vec2> bounds{r};
  for (const auto& c : cuts) bounds.push_back(kAxes[c.second]);
  bounds.push_back(l);
  for (std::size_t i = 0; i + 1 < bounds.size(); ++i) {
    const Vec2 s = bounds[i], e = bounds[i + 1];
    if (s == e) continue;
    const Vec2 m = s + e;
    const bool upper = m.y > 0, east = m.x > 0;
    if (east && upper)  // quadrant I: East+, counter-clockwise from east
      out.push_back({{s, zero}, {e, zero}, +1, s == kAxes[0] ? static_cast<int>(K::east_plus) : -1});
    else if (!east && upper)  // II: West-, clockwise from west
      out.push_back({{e, zero}, {s, zero}, -1, e == kAxes[2] ? static_cast<int>(K::west_minus) : -1});
    else if (!east && !upper)  // III: West+, counter-clockwise from west
      out.push_back({{s, zero}, {e, zero}, +1, s == kAxes[2] ? static_cast<int>(K::west_plus) : -1});
    else  // IV: East-, clockwise from east
      out.push_back({{e, zero}, {s, zero}, -1, e == kAxes[0] ? static_cast<int>(K::east_minus) : -1});
  }
  return out;
}

void VisibilityFan::sweep(Vec2 eye, const Piece& piece, Scratch& s, FanResult& out) const {
  const int sense = piece.sense;
  Dir cur = piece.start;
  bool first = true;
  for (std::size_t guard = 0;; ++guard) {
    if (guard > 4 * edges_.size() + 16) throw std::logic_error("polar fan: the sweep does not advance");
    const std::uint32_t hit = shoot(eye, cur, sense, s, out);
    const std::uint32_t end = far_end(hit, cur, eye, sense);
    std::int64_t next = end;
    if (first && piece.diagram >= 0 && edges_[hit].object == kFrame && options_.polar_start) {
      // Step 1: nothing just past the axis; the diagram names the first vertex any turning ray
      // meets, so no vertex lies before it and no wedge needs certifying.
      ++out.stats.polar_locates;
      const std::int64_t v = diagrams_.of(static_cast<DiagramKind>(piece.diagram)).first_vertex(eye);
      if (v >= 0 && sense * orient(eye, points_[end], points_[static_cast<std::size_t>(v)]) < 0) next = v;
      ++out.stats.polar_skips;
    } else if (options_.certify_wedges) {
      const std::int64_t v = first_in_front(eye, cur, hit, end, sense, out);
      if (v >= 0) {
        next = v;
        ++out.stats.wedge_splits;
      }
    }
    first = false;
    const std::uint32_t object = edges_[hit].object;
    if (object != kFrame) {
      if (s.object_query[object] != s.query) out.visible.push_back(ids_[object]);
      if (s.edge_query[hit] != s.query) out.visible_edges.push_back(hit);
      s.object_query[object] = s.edge_query[hit] = s.query;
    }
    const Vec2 n = points_[static_cast<std::size_t>(next)];
    if (side(piece.end, n, eye, sense) >= 0) return;  // the interval ends before the next direction
    cur = {n, eye};
  }
}

FanResult VisibilityFan::visible(Vec2 eye, const PlanWedge& wedge) const {
  if (!inside_frame(eye))
    throw std::invalid_argument("polar fan: the eye lies outside the scene's frame");
  Scratch& s = *scratch_;
  if (++s.query == 0) {
    std::fill(s.object_query.begin(), s.object_query.end(), 0u);
    std::fill(s.edge_query.begin(), s.edge_query.end(), 0u);
    s.query = 1;
  }
  FanResult out;
  for (const Piece& p : pieces(wedge)) sweep(eye, p, s, out);
  std::sort(out.visible.begin(), out.visible.end());
  std::sort(out.visible_edges.begin(), out.visible_edges.end());
  return out;
}

}  // namespace cullcheck::polar
