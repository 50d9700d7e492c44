#include "engine/slice_wise/occlusion_buffer.hpp"

#include <algorithm>
#include <cmath>

namespace cullcheck::slice_wise {
namespace {

constexpr double kSliverWidth = 1e-9;  // pixels: an uncovered piece thinner than this counts as covered
constexpr std::size_t kMaxFragmentsEvaluated = 256;
constexpr std::size_t kMaxCoverPieces = 64;

double cross2(Vec2 a, Vec2 b) { return a.x * b.y - a.y * b.x; }

// Corner k of a box: bit 0 picks x, bit 1 y, bit 2 z (set: the high side).
Vec3 corner(const Box3& b, int k) { return {(k & 1) ? b.hi.x : b.lo.x, (k & 2) ? b.hi.y : b.lo.y, (k & 4) ? b.hi.z : b.lo.z}; }

// A small convex polygon (a piece of a pixel square still uncovered).
struct Piece : ConvexPolygon {
  Piece() = default;
  Piece(const ConvexPolygon& c) : ConvexPolygon(c) {}
  double area2() const {
    double s = 0;
    for (int i = 0; i < n; ++i) s += cross2(p[i], p[(i + 1) % n]);
    return s;
  }
  // Twice the area over the perimeter: a sliver's width.
  double width() const {
    double perimeter = 0;
    for (int i = 0; i < n; ++i) {
      const Vec2 e = p[(i + 1) % n] - p[i];
      perimeter += std::sqrt(e.x * e.x + e.y * e.y);
    }
    return perimeter > 0 ? area2() / perimeter : 0.0;
  }
};

// The point where segment p-q crosses a line (side values sp, sq of opposite signs), computed from
// the lexicographically lower end point so that both triangles of a shared edge get the same bits.
Vec2 crossing(Vec2 p, Vec2 q, double sp, double sq) {
  if (q.x < p.x || (q.x == p.x && q.y < p.y)) std::swap(p, q), std::swap(sp, sq);
  return p + (q - p) * (sp / (sp - sq));
}

// The part of `in` on the left of a -> b (keep_left) or on its right, closed.
Piece clip(const Piece& in, Vec2 a, Vec2 b, bool keep_left) {
  Piece out;
  const Vec2 e = b - a;
  auto side = [&](Vec2 q) {
    const double s = cross2(e, q - a);
    return keep_left ? s : -s;
  };
  for (int i = 0; i < in.n; ++i) {
    const Vec2 p = in.p[i], q = in.p[(i + 1) % in.n];
    const double sp = side(p), sq = side(q);
    if (sp >= 0 && out.n < 12) out.p[out.n++] = p;
    if (((sp > 0 && sq < 0) || (sp < 0 && sq > 0)) && out.n < 12) out.p[out.n++] = crossing(p, q, sp, sq);
  }
  return out;
}

// `in` clipped to the guard band [-w, 2w] x [-h, 2h] around a w x h image, so that later clipping
// works on coordinates of the image's size (a triangle near the eye can project millions of
// pixels away).
Piece guard_band(const Piece& in, double w, double h) {
  Piece out = in;
  const Vec2 lo{-w, -h}, hi{2 * w, 2 * h};
  out = clip(out, {lo.x, hi.y}, lo, true);   // x >= lo.x
  out = clip(out, {hi.x, lo.y}, hi, true);   // x <= hi.x
  out = clip(out, lo, {hi.x, lo.y}, true);   // y >= lo.y
  out = clip(out, hi, {lo.x, hi.y}, true);   // y <= hi.y
  return out;
}

// 1/depth = A x + B y + C over a projected planar piece, from three of its points (pixel
// coordinates p, 1/depth w) spanning twice the area `area2` (non-zero).
struct InverseDepth {
  double A = 0, B = 0, C = 0;
  double at(double x, double y) const { return A * x + B * y + C; }
  // The least value over the pixel square [x, x + 1] x [y, y + 1] (affine: at a corner), and the
  // greatest.
  double least(double x, double y) const { return at(A > 0 ? x : x + 1, B > 0 ? y : y + 1); }
  double greatest(double x, double y) const { return at(A > 0 ? x + 1 : x, B > 0 ? y + 1 : y); }
};
InverseDepth inverse_depth(Vec2 p0, Vec2 p1, Vec2 p2, double w0, double w1, double w2, double area2) {
  InverseDepth d;
  d.A = ((w1 - w0) * (p2.y - p0.y) - (w2 - w0) * (p1.y - p0.y)) / area2;
  d.B = ((w2 - w0) * (p1.x - p0.x) - (w1 - w0) * (p2.x - p0.x)) / area2;
  d.C = w0 - d.A * p0.x - d.B * p0.y;
  return d;
}

// Convex hull (counter-clockwise, no repeated point) of `pts`, in place.
void convex_hull(std::vector<Vec2>& pts) {
  std::sort(pts.begin(), pts.end(), [](Vec2 a, Vec2 b) { return a.x < b.x || (a.x == b.x && a.y < b.y); });
  pts.erase(std::unique(pts.begin(), pts.end()), pts.end());
  if (pts.size() < 3) return;
  std::vector<Vec2> h(2 * pts.size());
  std::size_t k = 0;
  for (std::size_t i = 0; i < pts.size(); ++i) {
    while (k >= 2 && cross2(h[k - 1] - h[k - 2], pts[i] - h[k - 2]) <= 0) --k;
    h[k++] = pts[i];
  }
  for (std::size_t i = pts.size() - 1, t = k + 1; i-- > 0;) {
    while (k >= t && cross2(h[k - 1] - h[k - 2], pts[i] - h[k - 2]) <= 0) --k;
    h[k++] = pts[i];
  }
  h.resize(k - 1);
  pts = std::move(h);
}

// Row range [first, last] of pixels a y-extent touches, clamped to [0, count - 1]; false if none.
bool touched_range(double lo, double hi, int count, int& first, int& last) {
  if (!(hi >= 0.0) || !(lo <= double(count))) return false;
  first = static_cast<int>(std::floor(std::max(lo, 0.0)));
  last = static_cast<int>(std::floor(std::min(hi, double(count) - 0.5)));
  first = std::clamp(first, 0, count - 1), last = std::clamp(last, 0, count - 1);
  return first <= last;
}

}  // namespace

bool strip_extent(const Vec2* poly, int n, double y0, double y1, double& x_lo, double& x_hi) {
  x_lo = HUGE_VAL, x_hi = -HUGE_VAL;
  for (int i = 0; i < n; ++i) {
    const Vec2 p = poly[i], q = poly[(i + 1) % n];
    if (p.y >= y0 && p.y <= y1) x_lo = std::min(x_lo, p.x), x_hi = std::max(x_hi, p.x);
    for (double line : {y0, y1}) {
      if ((p.y - line) * (q.y - line) < 0) {
        const double x = p.x + (line - p.y) * (q.x - p.x) / (q.y - p.y);
        x_lo = std::min(x_lo, x), x_hi = std::max(x_hi, x);
      }
    }
  }
  return x_lo <= x_hi;
}

std::optional<PerspectiveView> zoomed_view(Vec3 eye, const Box3& box, int resolution, double near) {
  const Vec3 centre = (box.lo + box.hi) * 0.5;
  const Vec3 f = centre - eye;
  if (!(length(f) > 4 * near)) return std::nullopt;
  PerspectiveView v;
  v.eye = eye;
  v.forward = normalized(f);
  const Vec3 up_ref = std::abs(v.forward.z) < 0.9 ? Vec3{0, 0, 1} : Vec3{1, 0, 0};
  v.right = normalized(cross(v.forward, up_ref));
  v.up = cross(v.right, v.forward);
  v.width = v.height = resolution;
  v.near = near;
  double u0 = HUGE_VAL, u1 = -HUGE_VAL, v0 = HUGE_VAL, v1 = -HUGE_VAL;
  for (int k = 0; k < 8; ++k) {
    const Vec3 d = corner(box, k) - eye;
    const double z = dot(d, v.forward);
    if (!(z > 2 * near)) return std::nullopt;
    const double u = dot(d, v.right) / z, w = dot(d, v.up) / z;
    u0 = std::min(u0, u), u1 = std::max(u1, u), v0 = std::min(v0, w), v1 = std::max(v1, w);
  }
  constexpr double kMaxTangent = 5.671281819617709;  // tan 80°
  if (std::max({-u0, u1, -v0, v1}) > kMaxTangent) return std::nullopt;
  // A margin so that the corners lie strictly inside, and a window never thinner than 1e-9.
  const double mu = 1e-9 + 1e-6 * (u1 - u0), mv = 1e-9 + 1e-6 * (v1 - v0);
  v.u0 = u0 - mu, v.u1 = u1 + mu, v.v0 = v0 - mv, v.v1 = v1 + mv;
  return v;
}

std::array<PerspectiveView, 6> cube_views(Vec3 eye, int resolution, double near) {
  const Vec3 axes[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  std::array<PerspectiveView, 6> out;
  for (int k = 0; k < 6; ++k) {
    PerspectiveView& v = out[static_cast<std::size_t>(k)];
    v.eye = eye;
    v.forward = axes[k];
    const Vec3 up_ref = k < 4 ? Vec3{0, 0, 1} : Vec3{0, 1, 0};
    v.right = normalized(cross(v.forward, up_ref));
    v.up = cross(v.right, v.forward);
    v.width = v.height = resolution;
    v.near = near;
  }
  return out;
}

void OcclusionBuffer::reset(const PerspectiveView& view) {
  view_ = view;
  sx_ = view.width / (view.u1 - view.u0);
  sy_ = view.height / (view.v1 - view.v0);
  const std::size_t n = std::size_t(view.width) * std::size_t(view.height);
  full_.assign(n, HUGE_VAL);
  exact_.assign(n, HUGE_VAL);
  dirty_.assign(n, 0);
  head_.assign(n, -1);
  fragments_.clear();
  polygons_.clear();
  stats_ = {};
}

Vec3 OcclusionBuffer::to_camera(Vec3 p) const {
  const Vec3 d = p - view_.eye;
  return {dot(d, view_.right), dot(d, view_.up), dot(d, view_.forward)};
}

Vec2 OcclusionBuffer::to_pixel(Vec3 c) const { return {(c.x / c.z - view_.u0) * sx_, (c.y / c.z - view_.v0) * sy_}; }

void OcclusionBuffer::draw_triangle(Vec3 a, Vec3 b, Vec3 c) {
  const std::array<Vec3, 3> in{to_camera(a), to_camera(b), to_camera(c)};
  if (in[0].z >= view_.near && in[1].z >= view_.near && in[2].z >= view_.near) return raster_triangle(in);
  // Clip at the near plane: up to four vertices, drawn as a fan.
  std::array<Vec3, 4> poly;
  int n = 0;
  for (int i = 0; i < 3; ++i) {
    const Vec3 p = in[static_cast<std::size_t>(i)], q = in[static_cast<std::size_t>((i + 1) % 3)];
    const double sp = p.z - view_.near, sq = q.z - view_.near;
    if (sp >= 0) poly[static_cast<std::size_t>(n++)] = p;
    if ((sp > 0 && sq < 0) || (sp < 0 && sq > 0)) {
      Vec3 x = p + (q - p) * (sp / (sp - sq));
      x.z = view_.near;
      poly[static_cast<std::size_t>(n++)] = x;
    }
  }
  for (int k = 1; k + 1 < n; ++k) raster_triangle({poly[0], poly[static_cast<std::size_t>(k)], poly[static_cast<std::size_t>(k + 1)]});
}

void OcclusionBuffer::raster_triangle(const std::array<Vec3, 3>& cam) {
  std::array<Vec2, 3> p{to_pixel(cam[0]), to_pixel(cam[1]), to_pixel(cam[2])};
  std::array<double, 3> w{1.0 / cam[0].z, 1.0 / cam[1].z, 1.0 / cam[2].z};
  double area2 = cross2(p[1] - p[0], p[2] - p[0]);
  if (!std::isfinite(area2) || area2 == 0.0) return;  // no area: covers nothing
  if (area2 < 0) std::swap(p[1], p[2]), std::swap(w[1], w[2]), area2 = -area2;
  int r0, r1;
  if (!touched_range(std::min({p[0].y, p[1].y, p[2].y}), std::max({p[0].y, p[1].y, p[2].y}), view_.height, r0, r1)) return;
  if (std::max({p[0].x, p[1].x, p[2].x}) < 0 || std::min({p[0].x, p[1].x, p[2].x}) > view_.width) return;
  // 1/depth = A x + B y + C over the triangle.
  const InverseDepth plane = inverse_depth(p[0], p[1], p[2], w[0], w[1], w[2], area2);
  const double w_min = std::min({w[0], w[1], w[2]});
  Piece tri;
  tri.n = 3;
  tri.p[0] = p[0], tri.p[1] = p[1], tri.p[2] = p[2];
  const Piece poly = guard_band(tri, view_.width, view_.height);
  if (poly.n < 3) return;
  const auto index = static_cast<std::uint32_t>(polygons_.size());
  bool kept = false;
  ++stats_.triangles;
  auto inside = [&](Vec2 q) {
    for (int e = 0; e < poly.n; ++e)
      if (cross2(poly.p[(e + 1) % poly.n] - poly.p[e], q - poly.p[e]) < 0) return false;
    return true;
  };
  for (int r = r0; r <= r1; ++r) {
    double xa, xb;
    if (!strip_extent(poly.p.data(), poly.n, r, r + 1.0, xa, xb)) continue;
    int c0, c1;
    if (!touched_range(xa, xb, view_.width, c0, c1)) continue;
    for (int c = c0; c <= c1; ++c) {
      const double depth = 1.0 / std::max(plane.least(c, r), w_min);  // the greatest depth over the square
      const std::size_t px = std::size_t(r) * std::size_t(view_.width) + std::size_t(c);
      if (!(depth < full_[px])) continue;  // something nearer already covers the whole square
      const bool whole = inside({double(c), double(r)}) && inside({c + 1.0, double(r)}) && inside({double(c), r + 1.0}) &&
                         inside({c + 1.0, r + 1.0});
      dirty_[px] = 1;
      if (whole) {
        full_[px] = depth;
        ++stats_.full_pixels;
      } else {
        fragments_.push_back({index, head_[px], depth});
        head_[px] = static_cast<std::int32_t>(fragments_.size() - 1);
        kept = true;
        ++stats_.fragments;
      }
    }
  }
  if (kept) polygons_.push_back(poly);  // as drawn
}

double OcclusionBuffer::evaluate(std::size_t px) {
  if (!dirty_[px]) return exact_[px];
  dirty_[px] = 0;
  const double full = full_[px];
  std::vector<std::pair<double, std::uint32_t>> list;
  for (std::int32_t f = head_[px]; f >= 0; f = fragments_[static_cast<std::size_t>(f)].next) {
    const Fragment& fr = fragments_[static_cast<std::size_t>(f)];
    if (fr.depth < full) list.emplace_back(fr.depth, fr.triangle);
  }
  exact_[px] = full;
  if (list.empty()) return full;
  ++stats_.exact_evaluations;
  std::sort(list.begin(), list.end());
  if (list.size() > kMaxFragmentsEvaluated) list.resize(kMaxFragmentsEvaluated);  // give up beyond: not covered
  const double x = double(px % std::size_t(view_.width)), y = double(px / std::size_t(view_.width));
  std::vector<Piece> pieces(1), next;
  pieces[0].n = 4;
  pieces[0].p = {Vec2{x, y}, Vec2{x + 1, y}, Vec2{x + 1, y + 1}, Vec2{x, y + 1}};
  for (const auto& [depth, t] : list) {
    const ConvexPolygon& poly = polygons_[t];
    next.clear();
    for (const Piece& piece : pieces) {
      Piece rest = piece;
      for (int e = 0; e < poly.n && rest.n >= 3; ++e) {
        const Vec2 a = poly.p[static_cast<std::size_t>(e)], b = poly.p[static_cast<std::size_t>((e + 1) % poly.n)];
        Piece outside = clip(rest, a, b, false);
        if (outside.n >= 3 && outside.width() > kSliverWidth) next.push_back(outside);
        rest = clip(rest, a, b, true);
      }
    }
    if (next.size() > kMaxCoverPieces) return exact_[px];  // too fragmented to settle: not covered below `full`
    pieces.swap(next);
    if (pieces.empty()) return exact_[px] = depth;
  }
  return exact_[px];
}

bool OcclusionBuffer::hidden_at(std::size_t px, double depth) {
  if (full_[px] < depth) return true;
  if (!dirty_[px]) return exact_[px] < depth;
  bool any = false;
  for (std::int32_t f = head_[px]; f >= 0 && !any; f = fragments_[static_cast<std::size_t>(f)].next)
    any = fragments_[static_cast<std::size_t>(f)].depth < depth;
  if (!any) return false;
  return evaluate(px) < depth;
}

double OcclusionBuffer::covered_depth(int x, int y) { return evaluate(std::size_t(y) * std::size_t(view_.width) + std::size_t(x)); }

BoxVisibility OcclusionBuffer::locate_box(const Box3& box, std::vector<Vec2>& hull) const {
  BoxVisibility out;
  std::array<Vec3, 8> c;
  for (int k = 0; k < 8; ++k)
    c[static_cast<std::size_t>(k)] = to_camera(corner(box, k));
  double lo = HUGE_VAL, hi = -HUGE_VAL;
  for (const Vec3& p : c) lo = std::min(lo, p.z), hi = std::max(hi, p.z);
  out.farthest = hi;
  out.crosses_near = lo < view_.near;
  out.nearest = std::max(lo, view_.near);
  hull.clear();
  if (hi < view_.near) return out;
  for (const Vec3& p : c)
    if (p.z >= view_.near) hull.push_back(to_pixel(p));
  if (out.crosses_near) {
    for (int k = 0; k < 8; ++k)
      for (int bit : {1, 2, 4}) {
        if (k & bit) continue;
        const Vec3 p = c[static_cast<std::size_t>(k)], q = c[static_cast<std::size_t>(k | bit)];
        const double sp = p.z - view_.near, sq = q.z - view_.near;
        if ((sp > 0 && sq < 0) || (sp < 0 && sq > 0)) {
          Vec3 x = p + (q - p) * (sp / (sp - sq));
          x.z = view_.near;
          hull.push_back(to_pixel(x));
        }
      }
  }
  convex_hull(hull);
  if (hull.empty()) return out;
  double x0 = HUGE_VAL, x1 = -HUGE_VAL, y0 = HUGE_VAL, y1 = -HUGE_VAL;
  for (Vec2 p : hull) x0 = std::min(x0, p.x), x1 = std::max(x1, p.x), y0 = std::min(y0, p.y), y1 = std::max(y1, p.y);
  out.in_image = x1 >= 0 && y1 >= 0 && x0 <= view_.width && y0 <= view_.height;
  out.beyond_image = x0 < 0 || y0 < 0 || x1 > view_.width || y1 > view_.height;
  return out;
}

BoxVisibility OcclusionBuffer::test_box(const Box3& box) {
  std::vector<Vec2>& hull = hull_;
  BoxVisibility out = locate_box(box, hull);
  ++stats_.box_tests;
  if (!out.in_image) return out;
  if (hull.size() < 3) {  // a degenerate (flat, edge-on) projection: taken as visible
    out.visible = true;   // rare; conservative
    return out;
  }
  // The box's depth over a pixel: a ray that meets the box enters it through a face turned to the
  // eye, so over pixel Q the box lies no nearer than the least depth of those faces over Q (1/depth
  // is affine over each face's projection). Faces reaching nearer than the near plane: the box's
  // least depth alone.
  struct Face {
    std::array<Vec2, 4> quad;
    InverseDepth plane;
  };
  std::vector<Face> faces;
  bool per_pixel = true;
  for (int axis = 0; axis < 3 && per_pixel; ++axis) {
    const double e = axis == 0 ? view_.eye.x : axis == 1 ? view_.eye.y : view_.eye.z;
    const double lo = axis == 0 ? box.lo.x : axis == 1 ? box.lo.y : box.lo.z;
    const double hi = axis == 0 ? box.hi.x : axis == 1 ? box.hi.y : box.hi.z;
    if (e >= lo && e <= hi) continue;
    const int side = e < lo ? 0 : 1;
    std::array<Vec3, 4> corners;
    for (int k = 0; k < 4; ++k) {
      // Around the face: (u, v) = (0,0), (1,0), (1,1), (0,1) over the other two axes.
      const int u = k == 1 || k == 2, v = k >= 2;
      corners[static_cast<std::size_t>(k)] = to_camera(corner(box, side << axis | u << (axis + 1) % 3 | v << (axis + 2) % 3));
      if (!(corners[static_cast<std::size_t>(k)].z >= view_.near)) per_pixel = false;
    }
    if (!per_pixel) break;
    Face f;
    std::array<double, 4> w;
    for (std::size_t k = 0; k < 4; ++k) f.quad[k] = to_pixel(corners[k]), w[k] = 1.0 / corners[k].z;
    const Vec2 p0 = f.quad[0], p1 = f.quad[1], p2 = f.quad[2];
    const double area2 = cross2(p1 - p0, p2 - p0);
    if (!std::isfinite(area2) || area2 == 0.0) continue;  // seen edge-on: no ray enters through it
    f.plane = inverse_depth(p0, p1, p2, w[0], w[1], w[2], area2);
    faces.push_back(f);
  }
  if (!per_pixel) faces.clear();
  double y0 = HUGE_VAL, y1 = -HUGE_VAL;
  for (Vec2 p : hull) y0 = std::min(y0, p.y), y1 = std::max(y1, p.y);
  int r0, r1;
  if (!touched_range(y0, y1, view_.height, r0, r1)) return out;
  std::vector<std::pair<double, double>> face_rows(faces.size());
  for (int r = r0; r <= r1; ++r) {
    double xa, xb;
    if (!strip_extent(hull.data(), int(hull.size()), r, r + 1.0, xa, xb)) continue;
    int c0, c1;
    if (!touched_range(xa, xb, view_.width, c0, c1)) continue;
    for (std::size_t f = 0; f < faces.size(); ++f)
      if (!strip_extent(faces[f].quad.data(), 4, r, r + 1.0, face_rows[f].first, face_rows[f].second))
        face_rows[f] = {HUGE_VAL, -HUGE_VAL};
    for (int c = c0; c <= c1; ++c) {
      double depth = out.nearest;
      if (!faces.empty()) {
        double least = HUGE_VAL;
        for (std::size_t f = 0; f < faces.size(); ++f) {
          if (face_rows[f].first > c + 1.0 || face_rows[f].second < c) continue;  // the face misses this pixel
          least = std::min(least, 1.0 / faces[f].plane.greatest(c, r));
        }
        if (least < HUGE_VAL) depth = std::max(depth, least);
      }
      if (!hidden_at(std::size_t(r) * std::size_t(view_.width) + std::size_t(c), depth)) {
        out.visible = true;
        return out;
      }
    }
  }
  return out;
}

}  // namespace cullcheck::slice_wise
