#include "reports/echo_image.hpp"

#include <algorithm>
#include <cmath>

namespace cullcheck {
namespace {

bool contains(const std::vector<std::uint32_t>& sorted, std::uint32_t t) { return std::binary_search(sorted.begin(), sorted.end(), t); }

// Calls f(i, j, triangle or -1, its upward normal and centre) for every pixel; pixel (i, j) shows
// plan point transmitter + ((i + 0.5) / size - 0.5, 0.5 - (j + 0.5) / size) * 2 range: a roof
// when one stands there (buildings may be absent), else the terrain.
template <class F>
void for_each_pixel(const Terrain& terrain, const TerrainScene* buildings, Vec3 transmitter, double range, int size, F&& f) {
  const std::int64_t first_building = std::int64_t(terrain.triangle_count());
  for (int j = 0; j < size; ++j)
    for (int i = 0; i < size; ++i) {
      const Vec2 p{transmitter.x + ((i + 0.5) / size - 0.5) * 2 * range, transmitter.y + (0.5 - (j + 0.5) / size) * 2 * range};
      double roof = 0.0;
      const std::int64_t r = buildings ? roof_triangle_at(*buildings, p, &roof) : -1;
      if (r >= 0) {
        f(i, j, first_building + r, Vec3{0, 0, 1}, Vec3{p.x, p.y, roof});
        continue;
      }
      const std::int64_t t = triangle_at(terrain, p);
      if (t < 0) {
        f(i, j, t, Vec3{}, Vec3{});
        continue;
      }
      const auto v = terrain.triangle(std::size_t(t));
      f(i, j, t, cross(v[1] - v[0], v[2] - v[0]), (v[0] + v[1] + v[2]) * (1.0 / 3));
    }
}

void draw_overlay(RgbImage& image, double range, int size) {
  // Rings at 1/5 .. 5/5 of the range, one pixel wide.
  const double centre = 0.5 * size, pixels_per_metre = size / (2 * range);
  for (int j = 0; j < size; ++j)
    for (int i = 0; i < size; ++i) {
      const double r = std::hypot(i + 0.5 - centre, j + 0.5 - centre) / pixels_per_metre;
      for (int k = 1; k <= 5; ++k)
        if (std::abs(r - range * k / 5) * pixels_per_metre < 0.5) image.set(i, j, echo_colours::kRing);
    }
  const int c = size / 2;
  for (int d = -4; d <= 4; ++d) image.set(c + d, c, echo_colours::kTransmitter), image.set(c, c + d, echo_colours::kTransmitter);
}

RgbImage echo(const Terrain& terrain, const TerrainScene* buildings, const std::vector<std::uint32_t>& visible, Vec3 transmitter,
              double range, int size) {
  RgbImage image(size, size, echo_colours::kOffTerrain);
  for_each_pixel(terrain, buildings, transmitter, range, size, [&](int i, int j, std::int64_t t, Vec3 n, Vec3 centre) {
    if (t < 0) return;
    if (!contains(visible, std::uint32_t(t))) return image.set(i, j, echo_colours::kNoReturn);
    const Vec3 to = transmitter - centre;
    const double facing = std::max(0.0, dot(n, to) / std::sqrt(dot(n, n) * dot(to, to)));
    const auto level = std::uint8_t(std::lround(60 + 195 * facing));
    image.set(i, j, {std::uint8_t(level / 4), level, std::uint8_t(level / 3)});
  });
  draw_overlay(image, range, size);
  return image;
}

RgbImage difference(const Terrain& terrain, const TerrainScene* buildings, const std::vector<std::uint32_t>& pvs,
                    const std::vector<std::uint32_t>& witnessed, Vec3 transmitter, double range, int size) {
  RgbImage image(size, size, echo_colours::kOffTerrain);
  for_each_pixel(terrain, buildings, transmitter, range, size, [&](int i, int j, std::int64_t t, Vec3, Vec3) {
    if (t < 0) return;
    const bool in_pvs = contains(pvs, std::uint32_t(t)), seen = contains(witnessed, std::uint32_t(t));
    image.set(i, j, in_pvs && seen ? echo_colours::kBoth
                    : in_pvs       ? echo_colours::kOverEstimate
                    : seen         ? echo_colours::kMissed
                                   : echo_colours::kNeither);
  });
  draw_overlay(image, range, size);
  return image;
}

}  // namespace

std::int64_t triangle_at(const Terrain& t, Vec2 p) {
  const double u = (p.x - t.corner.x) / t.dx, w = (p.y - t.corner.y) / t.dy;
  if (!(u >= 0.0 && w >= 0.0 && u < t.nx - 1 && w < t.ny - 1)) return -1;
  const auto i = std::uint32_t(u), j = std::uint32_t(w);
  const std::size_t tri = 2 * (std::size_t(j) * (t.nx - 1) + i) + (u - i >= w - j ? 0 : 1);
  return t.triangle_present(tri) ? std::int64_t(tri) : -1;
}

RgbImage echo_image(const Terrain& terrain, const std::vector<std::uint32_t>& visible, Vec3 transmitter, double range, int size) {
  return echo(terrain, nullptr, visible, transmitter, range, size);
}
RgbImage echo_image(const TerrainScene& scene, const std::vector<std::uint32_t>& visible, Vec3 transmitter, double range, int size) {
  return echo(scene.terrain, &scene, visible, transmitter, range, size);
}
RgbImage echo_difference_image(const Terrain& terrain, const std::vector<std::uint32_t>& pvs, const std::vector<std::uint32_t>& witnessed,
                               Vec3 transmitter, double range, int size) {
  return difference(terrain, nullptr, pvs, witnessed, transmitter, range, size);
}
RgbImage echo_difference_image(const TerrainScene& scene, const std::vector<std::uint32_t>& pvs, const std::vector<std::uint32_t>& witnessed,
                               Vec3 transmitter, double range, int size) {
  return difference(scene.terrain, &scene, pvs, witnessed, transmitter, range, size);
}

}  // namespace cullcheck
