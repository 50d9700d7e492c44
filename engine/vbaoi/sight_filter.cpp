#include "engine/vbaoi/sight_filter.hpp"

#include <algorithm>
#include <cmath>

#include "engine/shrinking/region_shrinking.hpp"

namespace cullcheck::vbaoi {
namespace {

constexpr double kRelative = 1e-9;     // margin on distances and tangents, relative
constexpr std::int64_t kMaxCells = 4'000'000;
// Each prism occludes only by its part this far inside its walls: the oracle's line of sight is
// cast in single precision, so a sight line cutting a corner by micrometres may pass it there
// (the 1,000-client run had one, 2.6e-6 m into a corner 1,900 m from the origin). 1 cm plus a
// float's resolution at the prism's coordinates.
double wall_margin(const std::vector<Vec2>& ring) {
  double extent = 0.0;
  for (Vec2 p : ring) extent = std::max({extent, std::abs(p.x), std::abs(p.y)});
  return 0.01 + 1e-6 * extent;
}

}  // namespace

SightFilter::SightFilter(const Scene& scene, double eye_height, double cell) : cell_(cell) {
  const double margin = kRelative * (1.0 + std::abs(eye_height));
  Box2 extent;
  for (const Building& b : scene.buildings) {
    if (!(b.bounds.lo.z < eye_height - margin)) continue;  // standing above the eyes
    for (const ConvexVerticalPrism& prism : b.prisms) {
      if (!(prism.height > eye_height + margin) || prism.ring.size() < 3) continue;  // the eyes see over it
      Blocker blocker{prism.ring};
      const double area = signed_area(blocker.ring);
      if (!(std::abs(area) > 0.0) || !std::isfinite(area)) continue;
      if (area < 0.0) std::reverse(blocker.ring.begin(), blocker.ring.end());
      auto inner = shrink_convex_ring(blocker.ring, wall_margin(blocker.ring));
      if (!inner) continue;  // thinner than the margin
      blocker.ring = std::move(*inner);
      for (Vec2 p : blocker.ring) extent.extend(p);
      blockers_.push_back(std::move(blocker));
    }
  }
  if (blockers_.empty()) return;
  // A city too large for the grid gets larger cells rather than running out of memory.
  const double width = extent.hi.x - extent.lo.x, depth = extent.hi.y - extent.lo.y;
  cell_ = std::max({cell_, std::sqrt(width * depth / static_cast<double>(kMaxCells)), 1e-3});
  origin_ = extent.lo;
  columns_ = static_cast<std::int64_t>(width / cell_) + 1;
  rows_ = static_cast<std::int64_t>(depth / cell_) + 1;
  cells_.resize(static_cast<std::size_t>(columns_ * rows_));
  for (std::uint32_t k = 0; k < blockers_.size(); ++k) {
    Box2 box;
    for (Vec2 p : blockers_[k].ring) box.extend(p);
    const auto c0 = static_cast<std::int64_t>((box.lo.x - origin_.x) / cell_), c1 = static_cast<std::int64_t>((box.hi.x - origin_.x) / cell_);
    const auto r0 = static_cast<std::int64_t>((box.lo.y - origin_.y) / cell_), r1 = static_cast<std::int64_t>((box.hi.y - origin_.y) / cell_);
    for (std::int64_t r = r0; r <= std::min(r1, rows_ - 1); ++r)
      for (std::int64_t c = c0; c <= std::min(c1, columns_ - 1); ++c) cells_[static_cast<std::size_t>(r * columns_ + c)].push_back(k);
  }
  seen_.assign(blockers_.size(), 0);
}

bool SightFilter::covers(const Blocker& blocker, Vec2 from, Vec2 u, Vec2 v, double limit, double reach, Interval& out) {
  ++prisms_tested_;
  // The prism in the frame (a along the line of sight, b across), cut to a >= front: the part
  // behind the eye cannot block a ray towards the disc, and in front every vertex has a tangent.
  const double front = kRelative * (1.0 + reach);
  clipped_.clear();
  const std::size_t n = blocker.ring.size();
  Vec2 first{dot(blocker.ring[0] - from, u), dot(blocker.ring[0] - from, v)};
  Vec2 p = first;
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2 q = i + 1 < n ? Vec2{dot(blocker.ring[i + 1] - from, u), dot(blocker.ring[i + 1] - from, v)} : first;
    if (p.x >= front) clipped_.push_back(p);
    if ((p.x >= front) != (q.x >= front)) {
      const double s = (front - p.x) / (q.x - p.x);
      clipped_.push_back({front, p.y + s * (q.y - p.y)});
    }
    p = q;
  }
  if (clipped_.size() < 3) return false;
  double t_min = HUGE_VAL, t_max = -HUGE_VAL;
  for (Vec2 c : clipped_) {
    const double t = c.y / c.x;
    t_min = std::min(t_min, t);
    t_max = std::max(t_max, t);
  }
  // The prism's own edge rays graze a vertex, where rounding decides a hit: keep clear of them.
  const double lo = std::max(t_min + kRelative * (1.0 + std::abs(t_min)), -limit);
  const double hi = std::min(t_max - kRelative * (1.0 + std::abs(t_max)), limit);
  if (!(lo < hi)) return false;
  // Distance at which the ray of tangent t enters the prism (Cyrus-Beck), +inf when it misses.
  auto entry = [&](double t) {
    double enter = -HUGE_VAL, leave = HUGE_VAL;
    for (std::size_t i = 0, m = clipped_.size(); i < m; ++i) {
      const Vec2 a = clipped_[i], e = clipped_[(i + 1) % m] - a;
      const Vec2 outward{e.y, -e.x};
      const double along = outward.x + outward.y * t, offset = dot(outward, a);
      if (along < 0.0) enter = std::max(enter, offset / along);
      else if (along > 0.0) leave = std::min(leave, offset / along);
      else if (offset < 0.0) return HUGE_VAL;
    }
    if (!(enter <= leave) || !(enter > 0.0)) return HUGE_VAL;
    return enter * std::sqrt(1.0 + t * t);
  };
  double farthest = std::max(entry(lo), entry(hi));
  for (Vec2 c : clipped_) {
    const double t = c.y / c.x;
    if (t > lo && t < hi) farthest = std::max(farthest, length(c));
  }
  if (!(farthest < reach)) return false;
  out = {lo, hi};
  return true;
}

bool SightFilter::hidden(Vec2 from, Vec2 to, double radius) {
  if (blockers_.empty()) return false;
  const Vec2 d = to - from;
  const double dist = length(d);
  if (!std::isfinite(dist) || !std::isfinite(radius) || !(radius >= 0.0)) return false;
  const double reach = dist - radius - kRelative * (1.0 + dist);  // every point of the disc is farther
  if (!(reach > 0.0)) return false;
  const Vec2 u = d * (1.0 / dist), v{-u.y, u.x};
  // The directions towards the disc: tangents within tan(asin(radius / dist)).
  const double limit = radius / std::sqrt((dist - radius) * (dist + radius)) * (1.0 + kRelative) + kRelative;
  if (++call_ == 0) {
    std::fill(seen_.begin(), seen_.end(), 0u);
    call_ = 1;
  }
  intervals_.clear();
  // Grid cells that meet the capsule of radius r around the segment (it holds every segment from
  // `from` to the disc), column by column along the major axis, nearest to `from` first.
  const double r = radius + kRelative * (1.0 + dist);
  const bool along_x = std::abs(d.x) >= std::abs(d.y);
  auto major = [&](Vec2 p) { return along_x ? p.x : p.y; };
  auto minor = [&](Vec2 p) { return along_x ? p.y : p.x; };
  const double major_origin = along_x ? origin_.x : origin_.y, minor_origin = along_x ? origin_.y : origin_.x;
  const std::int64_t major_cells = along_x ? columns_ : rows_, minor_cells = along_x ? rows_ : columns_;
  const double m0 = std::min(major(from), major(to)), m1 = std::max(major(from), major(to));
  const double slope = minor(d) / major(d);
  auto minor_at = [&](double m) { return minor(from) + (std::clamp(m, m0, m1) - major(from)) * slope; };
  auto index = [&](double x, double origin, std::int64_t cells) {
    return std::clamp<std::int64_t>(static_cast<std::int64_t>(std::floor((x - origin) / cell_)), -1, cells);
  };
  const std::int64_t first = index(m0 - r, major_origin, major_cells), last = index(m1 + r, major_origin, major_cells);
  const bool forward = major(d) > 0.0;
  for (std::int64_t step = 0; step <= last - first; ++step) {
    const std::int64_t i = forward ? first + step : last - step;
    if (i < 0 || i >= major_cells) continue;
    const double x0 = major_origin + static_cast<double>(i) * cell_;
    const double ya = minor_at(x0 - r), yb = minor_at(x0 + cell_ + r);
    const std::int64_t j0 = index(std::min(ya, yb) - r, minor_origin, minor_cells);
    const std::int64_t j1 = index(std::max(ya, yb) + r, minor_origin, minor_cells);
    for (std::int64_t j = std::max<std::int64_t>(j0, 0); j <= std::min(j1, minor_cells - 1); ++j) {
      const std::int64_t c = along_x ? j * columns_ + i : i * columns_ + j;
      for (std::uint32_t k : cells_[static_cast<std::size_t>(c)]) {
        if (seen_[k] == call_) continue;
        seen_[k] = call_;
        Interval part;
        if (!covers(blockers_[k], from, u, v, limit, reach, part)) continue;
        if (part.lo <= -limit && part.hi >= limit) return true;
        intervals_.push_back(part);
      }
    }
  }
  // Several prisms together (a building's convex parts, or neighbours overlapping in direction).
  std::sort(intervals_.begin(), intervals_.end(), [](const Interval& a, const Interval& b) { return a.lo < b.lo; });
  double covered = -limit;
  for (const Interval& part : intervals_) {
    if (part.lo > covered) return false;
    covered = std::max(covered, part.hi);
    if (covered >= limit) return true;
  }
  return false;
}

}  // namespace cullcheck::vbaoi
