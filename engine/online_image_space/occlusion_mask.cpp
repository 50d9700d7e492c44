#include "engine/online_image_space/occlusion_mask.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace cullcheck::online {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

// Keeps the part of a convex camera-space polygon at depth >= near (Sutherland-Hodgman, one plane).
int clip_to_near(const std::vector<Vec3>& in, int n, double near, std::vector<Vec3>& out) {
  out.resize(std::size_t(2 * n));
  int m = 0;
  for (int i = 0; i < n; ++i) {
    const Vec3 a = in[std::size_t(i)], b = in[std::size_t((i + 1) % n)];
    const bool a_in = a.z >= near, b_in = b.z >= near;
    if (a_in) out[std::size_t(m++)] = a;
    if (a_in != b_in) {
      const double t = (near - a.z) / (b.z - a.z);
      out[std::size_t(m++)] = {a.x + (b.x - a.x) * t, a.y + (b.y - a.y) * t, near};
    }
  }
  return m;
}

// 1 where every pixel within Chebyshev distance r along one axis is set (outside counts unset).
void erode_line(const std::uint8_t* in, std::uint8_t* out, int n, std::ptrdiff_t stride, int r, std::vector<int>& prefix) {
  prefix.assign(std::size_t(n) + 1, 0);
  for (int i = 0; i < n; ++i) prefix[std::size_t(i) + 1] = prefix[std::size_t(i)] + (in[i * stride] ? 0 : 1);
  for (int i = 0; i < n; ++i) {
    const int lo = i - r, hi = i + r;
    out[i * stride] = lo >= 0 && hi < n && prefix[std::size_t(hi) + 1] - prefix[std::size_t(lo)] == 0 ? 1 : 0;
  }
}

}  // namespace

DepthImage::DepthImage(const ImagePlane& plane)
    : plane_(plane), width_(plane.width()), height_(plane.height()), depth_(std::size_t(width_) * std::size_t(height_), kInfinity) {}

std::uint64_t DepthImage::draw(const Vec3* vertices, std::uint32_t count) {
  if (count < 3) return 0;
  // Scratch space kept between calls (roofs of round buildings can have many vertices).
  thread_local std::vector<Vec3> camera, clipped;
  thread_local std::vector<ViewPoint> p;
  camera.resize(count);
  for (std::uint32_t i = 0; i < count; ++i) camera[i] = plane_.to_camera(vertices[i]);
  const int n = clip_to_near(camera, int(count), plane_.near(), clipped);
  if (n < 3) return 0;
  // Plane n . p = c in camera space (Newell's normal), and 1/depth = (A x + B y + C) / c on the image.
  Vec3 normal{};
  double farthest = 0.0;
  for (int i = 0; i < n; ++i) {
    const Vec3 a = clipped[i], b = clipped[(i + 1) % n];
    normal.x += (a.y - b.y) * (a.z + b.z);
    normal.y += (a.z - b.z) * (a.x + b.x);
    normal.z += (a.x - b.x) * (a.y + b.y);
    farthest = std::max(farthest, a.z);
  }
  const double c = dot(normal, clipped[0]);
  const double scale = length(normal) * length(clipped[0]);
  if (!(std::abs(c) > 1e-12 * scale)) return 0;  // edge-on: the plane passes through the eye
  const double w = width_, h = height_, th = plane_.tan_half_h(), tv = plane_.tan_half_v();
  const double A = normal.x * 2.0 * th / w / c, B = -normal.y * 2.0 * tv / h / c;
  const double C = (normal.z - normal.x * th + normal.y * tv) / c;
  p.resize(std::size_t(n));
  double x_lo = kInfinity, x_hi = -kInfinity, y_lo = kInfinity, y_hi = -kInfinity, area = 0.0;
  for (int i = 0; i < n; ++i) {
    p[i] = plane_.project(clipped[i]);
    x_lo = std::min(x_lo, p[i].x), x_hi = std::max(x_hi, p[i].x), y_lo = std::min(y_lo, p[i].y), y_hi = std::max(y_hi, p[i].y);
  }
  for (int i = 0; i < n; ++i) area += p[i].x * p[(i + 1) % n].y - p[(i + 1) % n].x * p[i].y;
  if (area == 0.0 || !std::isfinite(area)) return 0;
  const double sign = area > 0 ? 1.0 : -1.0;
  // Pixel ranges clamped as doubles first: a vertex just past the near plane can project far off the image.
  const double fi0 = std::max(0.0, std::ceil(x_lo - 0.5)), fi1 = std::min(width_ - 1.0, std::floor(x_hi - 0.5));
  const double fj0 = std::max(0.0, std::ceil(y_lo - 0.5)), fj1 = std::min(height_ - 1.0, std::floor(y_hi - 0.5));
  if (!(fi0 <= fi1 && fj0 <= fj1)) return 0;
  const int i0 = int(fi0), i1 = int(fi1), j0 = int(fj0), j1 = int(fj1);
  std::uint64_t written = 0;
  for (int j = j0; j <= j1; ++j) {
    const double yc = j + 0.5;
    for (int i = i0; i <= i1; ++i) {
      const double xc = i + 0.5;
      bool inside = true;
      for (int k = 0; k < n && inside; ++k) {
        const ViewPoint a = p[k], b = p[(k + 1) % n];
        inside = sign * ((b.x - a.x) * (yc - a.y) - (b.y - a.y) * (xc - a.x)) >= 0.0;
      }
      if (!inside) continue;
      keep_deepest_corner(i, j, A, B, C, farthest);
      ++written;
    }
  }
  return written;
}

void DepthImage::keep_deepest_corner(int i, int j, double A, double B, double C, double cap) {
  // 1/depth = A x + B y + C over the pixel's square: the deepest point is at a corner.
  const double inv = std::min({A * i + B * j + C, A * (i + 1) + B * j + C, A * i + B * (j + 1) + C, A * (i + 1) + B * (j + 1) + C});
  const double deepest = inv > 0.0 ? std::min(1.0 / inv, cap) : cap;
  double& d = depth_[std::size_t(j) * std::size_t(width_) + std::size_t(i)];
  d = std::min(d, deepest);
}

std::uint64_t DepthImage::draw_ground(double far) {
  const Vec3 eye = plane_.eye();
  if (!(eye.z > 0.0)) return 0;
  // Camera space: the world's up is n = to_camera(eye + z) and the ground is n . p = -eye.z, so
  // 1/depth = (n . direction) / (-eye.z) is affine on the image.
  const Vec3 n = plane_.to_camera({eye.x, eye.y, eye.z + 1.0});
  const double w = width_, h = height_, th = plane_.tan_half_h(), tv = plane_.tan_half_v(), c = -eye.z;
  const double A = n.x * 2.0 * th / w / c, B = -n.y * 2.0 * tv / h / c, C = (n.z - n.x * th + n.y * tv) / c;
  std::uint64_t written = 0;
  for (int j = 0; j < height_; ++j)
    for (int i = 0; i < width_; ++i) {
      if (!(A * (i + 0.5) + B * (j + 0.5) + C > 0.0)) continue;  // the centre's ray misses the ground
      keep_deepest_corner(i, j, A, B, C, far);
      ++written;
    }
  return written;
}

OcclusionMask::OcclusionMask(const ImagePlane& plane, const DepthImage& image, int shrink_pixels) : plane_(plane) {
  const int w = image.width(), h = image.height();
  const int r = std::max(0, shrink_pixels) + 1;
  const std::vector<double>& raw = image.depth();
  std::vector<std::uint8_t> covered(raw.size()), rows(raw.size()), kept(raw.size());
  for (std::size_t i = 0; i < raw.size(); ++i) covered[i] = std::isfinite(raw[i]) ? 1 : 0;
  std::vector<int> prefix;
  for (int j = 0; j < h; ++j) erode_line(&covered[std::size_t(j) * std::size_t(w)], &rows[std::size_t(j) * std::size_t(w)], w, 1, r, prefix);
  for (int i = 0; i < w; ++i) erode_line(&rows[std::size_t(i)], &kept[std::size_t(i)], h, w, r, prefix);
  std::vector<double> m0(raw.size(), kInfinity);
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i) {
      if (!kept[std::size_t(j) * std::size_t(w) + std::size_t(i)]) continue;
      double deepest = 0.0;  // r >= 1, so the 3 x 3 pixels around a kept pixel are all inside and covered
      for (int dj = -1; dj <= 1; ++dj)
        for (int di = -1; di <= 1; ++di) deepest = std::max(deepest, raw[std::size_t(j + dj) * std::size_t(w) + std::size_t(i + di)]);
      m0[std::size_t(j) * std::size_t(w) + std::size_t(i)] = deepest;
    }
  levels_.push_back(std::move(m0));
  widths_.push_back(w), heights_.push_back(h);
}

void OcclusionMask::build_hierarchy(int block, int levels) {
  block_ = std::max(2, block);
  levels_.resize(1), widths_.resize(1), heights_.resize(1);
  while ((levels < 0 && (widths_.back() > 1 || heights_.back() > 1)) || int(levels_.size()) <= levels) {
    const int pw = widths_.back(), ph = heights_.back();
    if (pw == 1 && ph == 1) break;
    const int cw = (pw + block_ - 1) / block_, ch = (ph + block_ - 1) / block_;
    std::vector<double> coarse(std::size_t(cw) * std::size_t(ch), 0.0);
    const std::vector<double>& fine = levels_.back();
    for (int j = 0; j < ph; ++j)
      for (int i = 0; i < pw; ++i) {
        double& c = coarse[std::size_t(j / block_) * std::size_t(cw) + std::size_t(i / block_)];
        c = std::max(c, fine[std::size_t(j) * std::size_t(pw) + std::size_t(i)]);
      }
    levels_.push_back(std::move(coarse));
    widths_.push_back(cw), heights_.push_back(ch);
  }
}

std::uint64_t OcclusionMask::covered_pixels() const {
  return std::uint64_t(std::count_if(levels_[0].begin(), levels_[0].end(), [](double d) { return std::isfinite(d); }));
}

bool OcclusionMask::occluded(const Box3& box, MaskTest* stats) const {
  double x_lo = kInfinity, x_hi = -kInfinity, y_lo = kInfinity, y_hi = -kInfinity, nearest = kInfinity;
  for (int k = 0; k < 8; ++k) {
    const Vec3 corner{k & 1 ? box.hi.x : box.lo.x, k & 2 ? box.hi.y : box.lo.y, k & 4 ? box.hi.z : box.lo.z};
    const Vec3 c = plane_.to_camera(corner);
    if (!(c.z >= plane_.near())) return false;  // reaches the eye's side of the near plane
    const ViewPoint p = plane_.project(c);
    x_lo = std::min(x_lo, p.x), x_hi = std::max(x_hi, p.x), y_lo = std::min(y_lo, p.y), y_hi = std::max(y_hi, p.y);
    nearest = std::min(nearest, c.z);
  }
  const int g = plane_.guard(), w = widths_[0], h = heights_[0];
  if (!plane_.covers_view() && !(x_lo >= g && y_lo >= g && x_hi <= w - g && y_hi <= h - g)) return false;
  x_lo = std::max(x_lo, double(g)), y_lo = std::max(y_lo, double(g));
  x_hi = std::min(x_hi, double(w - g)), y_hi = std::min(y_hi, double(h - g));
  if (!(x_lo < x_hi && y_lo < y_hi)) return false;  // outside the clip region: not in view, nothing to mark
  const int x0 = int(x_lo), y0 = int(y_lo), x1 = std::min(w - g - 1, int(x_hi)), y1 = std::min(h - g - 1, int(y_hi));
  // Start at the coarsest level whose pixels are no larger than the rectangle: it meets at most
  // block + 1 of them each way.
  const long extent = std::max(x1 - x0, y1 - y0) + 1;
  int level = 0;
  for (long span = block_; level + 1 < int(levels_.size()) && span <= extent; span *= block_) ++level;
  return rectangle_behind(level, x0, y0, x1, y1, nearest, stats);
}

bool OcclusionMask::rectangle_behind(int level, int x0, int y0, int x1, int y1, double depth, MaskTest* stats) const {
  long size = 1;  // level-0 pixels per level-`level` pixel, each way
  for (int i = 0; i < level; ++i) size *= block_;
  const int w = widths_[std::size_t(level)];
  const std::vector<double>& cells = levels_[std::size_t(level)];
  for (long cy = y0 / size; cy <= y1 / size; ++cy)
    for (long cx = x0 / size; cx <= x1 / size; ++cx) {
      if (stats) ++stats->cells;
      if (cells[std::size_t(cy) * std::size_t(w) + std::size_t(cx)] < depth) continue;
      if (level == 0) return false;
      const int sx0 = std::max(x0, int(cx * size)), sx1 = std::min(x1, int((cx + 1) * size - 1));
      const int sy0 = std::max(y0, int(cy * size)), sy1 = std::min(y1, int((cy + 1) * size - 1));
      if (!rectangle_behind(level - 1, sx0, sy0, sx1, sy1, depth, stats)) return false;
    }
  return true;
}

}  // namespace cullcheck::online
