#include "generators/plan_scenes.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/random.hpp"
#include "core/scene_io.hpp"
#include "generators/grid_snap.hpp"
#include "generators/param_checks.hpp"
#include "generators/params_json.hpp"

namespace cullcheck::generators {
namespace {

double half_metres(Random& rng, double lo, double hi) {
  return 0.5 * static_cast<double>(rng.uniform_int(static_cast<std::int64_t>(std::ceil(2 * lo)), static_cast<std::int64_t>(std::floor(2 * hi))));
}

void add(Scene& s, std::vector<Vec2> ring, double height) {
  s.buildings.push_back(footprint_building(static_cast<ObjectId>(s.buildings.size()), std::move(ring), height));
}

std::vector<Vec2> star(Vec2 c, int n, double r_lo, double r_hi, Random& rng, bool alternate) {
  std::vector<Vec2> ring;
  const double phase = rng.uniform_real(0, 2 * M_PI / n);
  for (int k = 0; k < n; ++k) {
    const double a = phase + 2 * M_PI * k / n;
    const double r = alternate ? (k % 2 ? r_lo : r_hi) * rng.uniform_real(0.9, 1.0) : rng.uniform_real(r_lo, r_hi);
    ring.push_back(snap_mm(Vec2{c.x + r * std::cos(a), c.y + r * std::sin(a)}));  // libm tails differ: whole mm
  }
  return ring;
}

}  // namespace

void validate(const SlotCityParams& p, const std::string& generator) {
  const ParamChecks check("generator", generator);
  check.in_range("slots_x", p.slots_x, 1, 1000);
  check.in_range("slots_y", p.slots_y, 1, 1000);
  check.in_range("slot", p.slot, 4.0, 1000.0);
  check.above("height", p.height, 0.0, 1000.0);
}

void validate(const StarBlockParams& p, const std::string& generator) {
  const ParamChecks check("generator", generator);
  check.in_range("count", p.count, 0, 1'000'000);
  check.in_range("vertices", p.vertices, 3, 10'000);
  check.in_range("block", p.block, 1.0, 10'000.0);
  check.above("street", p.street, 0.0, p.block);
  check.above("min_height", p.min_height, 0.0, 1000.0);
  check.in_range("max_height", p.max_height, p.min_height, 1000.0);
}

Scene slot_city(const SlotCityParams& p, std::uint64_t seed) {
  validate(p);
  Scene s;
  const double S = p.slot;
  for (int j = 0; j < p.slots_y; ++j)
    for (int i = 0; i < p.slots_x; ++i) {
      Random rng = Random::stream(seed, 1, static_cast<std::uint64_t>(i), static_cast<std::uint64_t>(j));
      const double ox = i * S, oy = j * S;
      // Each side flush with the slot (touching the neighbour's flush side) half the time.
      auto lo = [&] { return rng.bernoulli(0.5) ? 0.0 : half_metres(rng, 0.5, S / 4); };
      auto hi = [&] { return rng.bernoulli(0.5) ? S : S - half_metres(rng, 0.5, S / 4); };
      const double x0 = ox + lo(), x1 = ox + hi(), y0 = oy + lo(), y1 = oy + hi();
      const double w = x1 - x0, h = y1 - y0;
      switch (rng.uniform_int(0, 4)) {
        case 0: break;  // an empty slot: a square to stand in
        case 1: add(s, {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}}, p.height); break;
        case 2: {  // L: the top right corner cut away
          const double cx = x0 + half_metres(rng, 0.5, w - 0.5), cy = y0 + half_metres(rng, 0.5, h - 0.5);
          add(s, {{x0, y0}, {x1, y0}, {x1, cy}, {cx, cy}, {cx, y1}, {x0, y1}}, p.height);
          break;
        }
        case 3: {  // U: a notch from the top, its arms at least half a metre wide
          const double arm = half_metres(rng, 0.5, std::max(0.5, w / 2 - 1.0));
          const double depth = half_metres(rng, 0.5, h - 0.5);
          add(s, {{x0, y0}, {x1, y0}, {x1, y1}, {x1 - arm, y1}, {x1 - arm, y1 - depth}, {x0 + arm, y1 - depth}, {x0 + arm, y1}, {x0, y1}},
              p.height);
          break;
        }
        default:
          add(s, star({ox + S / 2, oy + S / 2}, 2 * static_cast<int>(rng.uniform_int(4, 7)), S / 8, S * 0.45, rng, true), p.height);
      }
    }
  s.provenance = {"slot_city", seed, params_to_json(p).dump()};
  return s;
}

Scene star_block_city(const StarBlockParams& p, std::uint64_t seed) {
  validate(p);
  Scene s;
  const int columns = static_cast<int>(std::ceil(std::sqrt(static_cast<double>(p.count))));
  const double r = (p.block - p.street) / 2;
  for (int k = 0; k < p.count; ++k) {
    Random rng = Random::stream(seed, 2, static_cast<std::uint64_t>(k));
    const Vec2 c{(k % columns) * p.block, (k / columns) * p.block};
    // Two draws in a fixed order (function arguments are evaluated in either order).
    std::vector<Vec2> ring = star(c, p.vertices, 0.45 * r, r, rng, false);
    const double height = snap_mm(rng.uniform_real(p.min_height, p.max_height));
    add(s, std::move(ring), height);
  }
  s.provenance = {"star_block_city", seed, params_to_json(p).dump()};
  return s;
}

std::vector<Camera> star_block_walk(const StarBlockParams& p, int frames) {
  std::vector<Camera> out;
  const int columns = static_cast<int>(std::ceil(std::sqrt(static_cast<double>(p.count))));
  const int rows = (p.count + columns - 1) / columns;
  for (int i = 0; i < frames; ++i) {
    Camera c;
    const double along = (columns - 1) * p.block * i / std::max(1, frames - 1);
    const int street = i % 4;  // streets between rows street * rows / 4 and the next
    c.position = {along, p.block / 2 + std::floor(street * rows / 4.0) * p.block, 1.7};
    c.yaw = (i % 2 ? 1 : 3) * M_PI / 4 + 0.01 * i;
    c.hfov = M_PI / 2;
    c.vfov = M_PI / 4;
    out.push_back(c);
  }
  return out;
}

}  // namespace cullcheck::generators
