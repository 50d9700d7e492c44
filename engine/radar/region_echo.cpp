#include "engine/radar/region_echo.hpp"

#include <algorithm>
#include <cmath>
#include <deque>
#include <functional>
#include <stdexcept>

namespace cullcheck::radar {
namespace {

// Sliding minimum (or, with `Before` = std::greater, maximum) over ±k along one axis of an
// nx x ny row-major grid (a monotone deque: O(n)).
template <class Before = std::less<>>
std::vector<double> sliding_min(const std::vector<double>& in, std::uint32_t nx, std::uint32_t ny, std::uint32_t k, bool along_x) {
  const Before before;
  std::vector<double> out(in.size());
  const std::uint32_t lines = along_x ? ny : nx, n = along_x ? nx : ny;
  std::deque<std::uint32_t> window;  // positions along the line, their values ascending
  for (std::uint32_t l = 0; l < lines; ++l) {
    const auto at = [&](std::uint32_t i) { return along_x ? std::size_t(l) * nx + i : std::size_t(i) * nx + l; };
    window.clear();
    std::uint32_t next = 0;  // the next position to enter the window
    for (std::uint32_t i = 0; i < n; ++i) {
      for (; next < n && next <= i + k; ++next) {
        while (!window.empty() && !before(in[at(window.back())], in[at(next)])) window.pop_back();
        window.push_back(next);
      }
      while (window.front() + k < i) window.pop_front();
      out[at(i)] = in[at(window.front())];
    }
  }
  return out;
}

}  // namespace

ShrunkFloors eroded_floors(const RadarSurface& surface, double radius) {
  ShrunkFloors out;
  out.floors.assign(surface.triangle_count(), -HUGE_VAL);
  out.drops.assign(surface.triangle_count(), HUGE_VAL);
  std::vector<double>& floors = out.floors;
  if (surface.terrain_has_holes()) return out;
  const Terrain& t = surface.terrain();
  // A triangle's plan box grown by `radius` meets the cells of vertices [i0 - kx, i1 + kx] when
  // its own box spans vertices [i0, i1] (i0 = floor, i1 = ceil of its ends in vertex units).
  const auto kx = std::uint32_t(std::min<double>(t.nx, std::ceil(radius / t.dx)));
  const auto ky = std::uint32_t(std::min<double>(t.ny, std::ceil(radius / t.dy)));
  const std::vector<double> low = sliding_min(sliding_min(t.z, t.nx, t.ny, kx, true), t.nx, t.ny, ky, false);
  // Per cell, the steeper of its two triangles' gradients (split south-west to north-east), then
  // the steepest over ±k cells: the ground within `radius` of a point of a terrain triangle is
  // at most radius x that below it.
  const std::uint32_t cx = t.nx - 1, cy = t.ny - 1;
  std::vector<double> steep(std::size_t(cx) * cy);
  for (std::uint32_t j = 0; j < cy; ++j)
    for (std::uint32_t i = 0; i < cx; ++i) {
      const double sw = t.z[t.index(i, j)], se = t.z[t.index(i + 1, j)], ne = t.z[t.index(i + 1, j + 1)], nw = t.z[t.index(i, j + 1)];
      steep[std::size_t(j) * cx + i] =
          std::max(std::hypot((se - sw) / t.dx, (ne - se) / t.dy), std::hypot((ne - nw) / t.dx, (nw - sw) / t.dy));
    }
  const std::vector<double> steepest =
      sliding_min<std::greater<>>(sliding_min<std::greater<>>(steep, cx, cy, kx, true), cx, cy, ky, false);
  for (std::size_t tri = 0; tri < floors.size(); ++tri) {
    if (!surface.present(tri)) continue;
    const auto p = surface.triangle(tri);
    double lo_x = HUGE_VAL, hi_x = -HUGE_VAL, lo_y = HUGE_VAL, hi_y = -HUGE_VAL;
    for (const Vec3& v : p) lo_x = std::min(lo_x, v.x), hi_x = std::max(hi_x, v.x), lo_y = std::min(lo_y, v.y), hi_y = std::max(hi_y, v.y);
    const auto index = [](double u, std::uint32_t n, bool up) {
      const double f = up ? std::ceil(u) : std::floor(u);
      return std::uint32_t(std::clamp(f, 0.0, double(n - 1)));
    };
    const std::uint32_t i0 = index((lo_x - t.corner.x) / t.dx, t.nx, false), i1 = index((hi_x - t.corner.x) / t.dx, t.nx, true);
    const std::uint32_t j0 = index((lo_y - t.corner.y) / t.dy, t.ny, false), j1 = index((hi_y - t.corner.y) / t.dy, t.ny, true);
    double f = HUGE_VAL;
    for (std::uint32_t j = j0; j <= j1; ++j)
      for (std::uint32_t i = i0; i <= i1; ++i) f = std::min(f, low[t.index(i, j)]);
    floors[tri] = f;
    if (tri < t.triangle_count()) {  // a terrain triangle: one cell
      const std::size_t cell = tri / 2;
      out.drops[tri] = radius * steepest[cell] * (1.0 + 1e-9);
    }
  }
  return out;
}

RegionEcho::RegionEcho(const TriangleGrid& grid, std::uint32_t horizon_bins)
    : grid_(grid), echo_(grid, RadarRule::conservative, horizon_bins) {}

Echo RegionEcho::compute(const MastRegion& r, const Sector& sector) {
  if (!grid_.plan().contains(r.centre) || !std::isfinite(r.z_low) || !std::isfinite(r.z_high) || !(r.z_low <= r.z_high) ||
      !std::isfinite(r.radius) || !(r.radius >= 0.0))
    throw std::invalid_argument("RegionEcho: the region must be a disc of finite radius over the terrain with z_low <= z_high");
  if (r.radius != floors_radius_) {
    floors_ = eroded_floors(grid_.surface(), r.radius);
    floors_radius_ = r.radius;
  }
  return echo_.compute_shrunk({r.centre.x, r.centre.y, r.z_high}, sector, {&floors_.floors, &floors_.drops, r.radius, r.z_low});
}

}  // namespace cullcheck::radar
