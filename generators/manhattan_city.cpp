// Manhattan grid, plaza and default cities (see city.hpp).
#include <algorithm>
#include <nlohmann/json.hpp>

#include "core/scene_io.hpp"
#include "generators/city.hpp"
#include "generators/manhattan_layout.hpp"
#include "generators/param_checks.hpp"
#include "generators/params_json.hpp"
#include "generators/random.hpp"

namespace cullcheck::generators {
namespace {

// Stream tags: one stream per block and one for the plaza's kiosks (random.hpp explains why).
constexpr std::uint64_t kManhattanBlockStream = 0x4D414E48;  // "MANH"
constexpr std::uint64_t kKioskStream = 0x4B494F53;           // "KIOS"

Building mm_box_building(ObjectId id, const MillimetreBox& b, Millimetres height) {
  Building out;
  out.id = id;
  out.height = metres(height);
  out.footprint = {{metres(b.lo_x), metres(b.lo_y)}, {metres(b.hi_x), metres(b.lo_y)},
                   {metres(b.hi_x), metres(b.hi_y)}, {metres(b.lo_x), metres(b.hi_y)}};
  validate_and_finish(out);
  return out;
}

// One building inside one lot: a regular building spans a jittered share of the lot (inside the
// setback); a thin one is a slab across the lot, 0.5-2 m thick by default, the kind of occluder
// that an incremental horizon can step past in one frame (thesis Fig. 3.10).
Building lot_building(ObjectId id, const MillimetreBox& lot, const ManhattanParams& p, Random& rng) {
  const Millimetres setback = to_mm(p.setback);
  const MillimetreBox avail{lot.lo_x + setback, lot.lo_y + setback, lot.hi_x - setback, lot.hi_y - setback};
  const Millimetres aw = avail.hi_x - avail.lo_x, ad = avail.hi_y - avail.lo_y;
  const Millimetres height = rng.bernoulli(p.tower_fraction) ? draw_mm(rng, p.tower_min_height, p.tower_max_height)
                                                             : draw_mm(rng, p.min_height, p.max_height);
  auto jittered = [&](Millimetres span) {
    const auto cut = static_cast<Millimetres>(static_cast<double>(span) * p.width_jitter * rng.uniform01());
    return std::max<Millimetres>(span - cut, 1);
  };
  Millimetres w, d;
  if (rng.bernoulli(p.thin_fraction)) {
    const Millimetres thickness = draw_mm(rng, p.thin_min_width, p.thin_max_width);
    if (rng.bernoulli(0.5)) {
      w = jittered(aw), d = std::min(thickness, ad);  // long side along x
    } else {
      w = std::min(thickness, aw), d = jittered(ad);  // long side along y
    }
  } else {
    w = jittered(aw), d = jittered(ad);
  }
  const Millimetres x = avail.lo_x + rng.uniform_int(0, aw - w), y = avail.lo_y + rng.uniform_int(0, ad - d);
  return mm_box_building(id, {x, y, x + w, y + d}, height);
}

// Kiosks stand inside the emptied blocks only (2 m in from their edges), never on the streets,
// so a street walk crossing the plaza along its centre lines cannot enter one.
void add_kiosks(Scene& scene, const ManhattanLayout& layout, const ManhattanParams& p, std::uint64_t seed) {
  Random rng = Random::stream(seed, kKioskStream);
  const Millimetres inset = 2000, gap = 1000;
  std::vector<MillimetreBox> placed;
  for (int k = 0; k < p.kiosk_count; ++k) {
    for (int attempt = 0; attempt < 50; ++attempt) {
      const int i = static_cast<int>(rng.uniform_int(layout.plaza_x0, layout.plaza_x1 - 1));
      const int j = static_cast<int>(rng.uniform_int(layout.plaza_y0, layout.plaza_y1 - 1));
      const MillimetreBox block = layout.block_box(i, j);
      const Millimetres w = draw_mm(rng, p.kiosk_min_size, p.kiosk_max_size);
      const Millimetres d = draw_mm(rng, p.kiosk_min_size, p.kiosk_max_size);
      const Millimetres x = rng.uniform_int(block.lo_x + inset, block.hi_x - inset - w);
      const Millimetres y = rng.uniform_int(block.lo_y + inset, block.hi_y - inset - d);
      const MillimetreBox box{x, y, x + w, y + d};
      const bool clear = std::none_of(placed.begin(), placed.end(), [&](const MillimetreBox& o) {
        return box.lo_x < o.hi_x + gap && o.lo_x < box.hi_x + gap && box.lo_y < o.hi_y + gap && o.lo_y < box.hi_y + gap;
      });
      if (!clear) continue;
      placed.push_back(box);
      const Millimetres height = draw_mm(rng, p.kiosk_min_height, p.kiosk_max_height);
      scene.buildings.push_back(mm_box_building(static_cast<ObjectId>(scene.buildings.size()), box, height));
      break;
    }
  }
}

Scene manhattan_like(const ManhattanParams& p, std::uint64_t seed, const std::string& name) {
  validate(p, name);
  const ManhattanLayout layout = manhattan_layout(p);
  Scene scene;
  scene.provenance = {name, seed, params_to_json(p).dump()};
  scene.buildings.reserve(static_cast<std::size_t>(p.blocks_x) * p.blocks_y * p.buildings_per_block + p.kiosk_count);
  for (int j = 0; j < p.blocks_y; ++j) {
    for (int i = 0; i < p.blocks_x; ++i) {
      if (layout.is_plaza_block(i, j)) continue;
      Random rng = Random::stream(seed, kManhattanBlockStream, static_cast<std::uint64_t>(i), static_cast<std::uint64_t>(j));
      for (const MillimetreBox& lot : lots_of_block(layout.block_box(i, j), p.buildings_per_block))
        scene.buildings.push_back(lot_building(static_cast<ObjectId>(scene.buildings.size()), lot, p, rng));
    }
  }
  add_kiosks(scene, layout, p, seed);
  return scene;
}

}  // namespace

ManhattanParams plaza_params() {
  ManhattanParams p;
  p.plaza_blocks_x = 2, p.plaza_blocks_y = 2, p.kiosk_count = 6;
  return p;
}

ManhattanParams default_city_params() {
  ManhattanParams p;
  p.blocks_x = 12, p.blocks_y = 12, p.buildings_per_block = 20;
  p.thin_fraction = 0.12;
  p.plaza_blocks_x = 2, p.plaza_blocks_y = 2, p.kiosk_count = 8;
  return p;
}

void validate(const ManhattanParams& p, const std::string& generator) {
  const ParamChecks check("generator", generator);
  check.in_range("blocks_x", p.blocks_x, 1, 10000);
  check.in_range("blocks_y", p.blocks_y, 1, 10000);
  check.in_range("block_size", p.block_size, 1.0, 10000.0);
  check.in_range("street_width", p.street_width, 1.0, 1000.0);
  check.in_range("buildings_per_block", p.buildings_per_block, 1, 10000);
  const long long total = 1LL * p.blocks_x * p.blocks_y * p.buildings_per_block;
  if (total > static_cast<long long>(kMaxBuildings))
    check.fail("buildings_per_block", "blocks_x * blocks_y * buildings_per_block = " + std::to_string(total) +
                                          " exceeds the scene limit of 20,000,000 buildings");
  check.in_range("setback", p.setback, 0.0, p.block_size / 2);
  check.in_range("width_jitter", p.width_jitter, 0.0, 0.9);
  check.above("min_height", p.min_height, 0.0, kMaxHeight);
  check.in_range("max_height", p.max_height, p.min_height, kMaxHeight);
  check.in_range("tower_fraction", p.tower_fraction, 0.0, 1.0);
  check.above("tower_min_height", p.tower_min_height, 0.0, kMaxHeight);
  check.in_range("tower_max_height", p.tower_max_height, p.tower_min_height, kMaxHeight);
  check.in_range("thin_fraction", p.thin_fraction, 0.0, 1.0);
  check.in_range("thin_min_width", p.thin_min_width, 0.001, 1000.0);
  check.in_range("thin_max_width", p.thin_max_width, p.thin_min_width, 1000.0);
  // A lot must keep at least 1 cm of buildable width inside its setbacks.
  const Millimetres lot = narrowest_lot_side(to_mm(p.block_size), p.buildings_per_block);
  if (lot - 2 * to_mm(p.setback) < 10)
    check.fail("buildings_per_block", std::to_string(p.buildings_per_block) + " lots per block leave lots " +
                                          ParamChecks::text(metres(lot)) + " m wide, too narrow for a setback of " +
                                          ParamChecks::text(p.setback) + " m on each side");
  check.in_range("plaza_blocks_x", p.plaza_blocks_x, 0, p.blocks_x);
  check.in_range("plaza_blocks_y", p.plaza_blocks_y, 0, p.blocks_y);
  if ((p.plaza_blocks_x == 0) != (p.plaza_blocks_y == 0))
    check.fail("plaza_blocks_y", "plaza_blocks_x and plaza_blocks_y must both be 0 (no plaza) or both be > 0");
  check.in_range("kiosk_count", p.kiosk_count, 0, 1000);
  if (p.kiosk_count > 0 && p.plaza_blocks_x == 0) check.fail("kiosk_count", "kiosks need a plaza (plaza_blocks_x/y > 0)");
  check.above("kiosk_min_height", p.kiosk_min_height, 0.0, kMaxHeight);
  check.in_range("kiosk_max_height", p.kiosk_max_height, p.kiosk_min_height, kMaxHeight);
  check.in_range("kiosk_min_size", p.kiosk_min_size, 0.01, 1000.0);
  check.in_range("kiosk_max_size", p.kiosk_max_size, p.kiosk_min_size, 1000.0);
  if (p.kiosk_count > 0 && p.block_size - 4.0 < p.kiosk_max_size)
    check.fail("kiosk_max_size", "must leave 2 m to each edge of a plaza block (block_size " +
                                     ParamChecks::text(p.block_size) + " m)");
}

Scene manhattan_city(const ManhattanParams& p, std::uint64_t seed) { return manhattan_like(p, seed, "manhattan"); }

Scene plaza_city(const ManhattanParams& p, std::uint64_t seed) {
  if (p.plaza_blocks_x == 0) ParamChecks("generator", "plaza").fail("plaza_blocks_x", "a plaza city needs plaza_blocks_x/y > 0");
  return manhattan_like(p, seed, "plaza");
}

Scene default_city(std::uint64_t seed) { return manhattan_like(default_city_params(), seed, "default"); }

}  // namespace cullcheck::generators
