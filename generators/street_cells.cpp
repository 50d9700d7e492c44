#include "generators/street_cells.hpp"

#include <algorithm>

#include "generators/city.hpp"

namespace cullcheck::generators {
namespace {

std::vector<Vec2> rectangle(double x0, double y0, double x1, double y1) { return {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}}; }

}  // namespace

std::vector<NavigableRegion> street_cells(const ManhattanLayout& l) {
  const int nx = l.blocks_x, ny = l.blocks_y;
  // Street k (k = 0..n) spans [origin + k * pitch, origin + k * pitch + street]; block i spans
  // [origin + street + i * pitch, origin + (i + 1) * pitch].
  auto street_lo_x = [&](int k) { return metres(l.origin_x + k * l.pitch); };
  auto street_lo_y = [&](int k) { return metres(l.origin_y + k * l.pitch); };
  const double w = metres(l.street);
  std::vector<NavigableRegion> cells;
  auto add = [&](const char* kind, std::vector<Vec2> ring) {
    cells.push_back({static_cast<std::uint32_t>(cells.size()), kind, std::move(ring), {}});
    return cells.back().id;
  };
  auto crossing = [&](int k, int m) { return static_cast<std::uint32_t>(m * (nx + 1) + k); };
  for (int m = 0; m <= ny; ++m)
    for (int k = 0; k <= nx; ++k)
      add("crossing", rectangle(street_lo_x(k), street_lo_y(m), street_lo_x(k) + w, street_lo_y(m) + w));
  auto link = [&](std::uint32_t a, std::uint32_t b) {
    cells[a].neighbours.push_back(b);
    cells[b].neighbours.push_back(a);
  };
  // North-south stretch of street k between crossings (k, j) and (k, j + 1); ids kept to link
  // the plaza blocks.
  std::vector<std::uint32_t> ns((nx + 1) * ny), ew(nx * (ny + 1));
  for (int k = 0; k <= nx; ++k)
    for (int j = 0; j < ny; ++j) {
      const std::uint32_t id =
          add("street", rectangle(street_lo_x(k), street_lo_y(j) + w, street_lo_x(k) + w, street_lo_y(j + 1)));
      ns[k * ny + j] = id;
      link(id, crossing(k, j)), link(id, crossing(k, j + 1));
    }
  for (int m = 0; m <= ny; ++m)
    for (int i = 0; i < nx; ++i) {
      const std::uint32_t id =
          add("street", rectangle(street_lo_x(i) + w, street_lo_y(m), street_lo_x(i + 1), street_lo_y(m) + w));
      ew[m * nx + i] = id;
      link(id, crossing(i, m)), link(id, crossing(i + 1, m));
    }
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      if (!l.is_plaza_block(i, j)) continue;
      const MillimetreBox b = l.block_box(i, j);
      const std::uint32_t id = add("plaza", rectangle(metres(b.lo_x), metres(b.lo_y), metres(b.hi_x), metres(b.hi_y)));
      link(id, ns[i * ny + j]), link(id, ns[(i + 1) * ny + j]);
      link(id, ew[j * nx + i]), link(id, ew[(j + 1) * nx + i]);
    }
  for (NavigableRegion& c : cells) std::sort(c.neighbours.begin(), c.neighbours.end());
  return cells;
}

std::optional<std::vector<NavigableRegion>> street_cells_of(const Scene& scene) {
  const std::optional<ManhattanParams> p = manhattan_params_of(scene);
  if (!p) return std::nullopt;
  return street_cells(manhattan_layout(*p));
}

}  // namespace cullcheck::generators
