// The openings city (city.hpp: OpeningsParams): facade walls with openings, arcades and bridges,
// the cases 2.5D prisms cannot express, among ordinary buildings.
//
// Each block and each street front draws from its own stream keyed by position (random.hpp), so a
// block keeps its content when the city around it shrinks; only the choice of bridged streets
// depends on the city's size. Everything is placed in whole millimetres.
#include <algorithm>
#include <nlohmann/json.hpp>

#include "core/scene_io.hpp"
#include "generators/city.hpp"
#include "generators/manhattan_layout.hpp"
#include "generators/openings_geometry.hpp"
#include "generators/param_checks.hpp"
#include "generators/params_json.hpp"
#include "generators/random.hpp"

namespace cullcheck::generators {
namespace {

constexpr std::uint64_t kOpeningsBlockStream = 0x4F50424C;  // "OPBL"
constexpr std::uint64_t kFrontStream = 0x4F504652;          // "OPFR"
constexpr std::uint64_t kBridgeStream = 0x4F504252;         // "OPBR"
constexpr Millimetres kPier = 300;                          // least wall beside, above and below an opening

ManhattanParams street_grid(const OpeningsParams& p) {
  ManhattanParams m;
  m.blocks_x = p.blocks_x, m.blocks_y = p.blocks_y, m.block_size = p.block_size, m.street_width = p.street_width;
  m.buildings_per_block = 1, m.setback = 0.0;
  return m;
}

class CityBuilder {
 public:
  CityBuilder(const OpeningsParams& p, std::uint64_t seed) : p_(p), seed_(seed) {
    scene_.provenance = {"openings", seed, params_to_json(p).dump()};
  }

  ObjectId next_id() { return static_cast<ObjectId>(next_id_++); }

  // An ordinary building on the box [u0, u1] x [v0, v1] of a frame.
  void building(const PlanFrame& f, Millimetres u0, Millimetres v0, Millimetres u1, Millimetres v1, Millimetres height) {
    const Vec3 a = f.place(u0, v0, 0), b = f.place(u1, v1, 0);
    Building out = box_building(next_id(), std::min(a.x, b.x), std::min(a.y, b.y), std::max(a.x, b.x), std::max(a.y, b.y),
                                metres(height));
    scene_.buildings.push_back(std::move(out));
  }

  void mesh(MeshObject m, const char* name) {
    m.id = next_id();
    m.name = name;
    validate_and_finish(m);
    scene_.meshes.push_back(std::move(m));
  }

  // The openings of one facade wall: bays along it, storeys up it, a door or a window per bay and
  // storey at most, kPier of wall between any two and around each; at least one on the ground
  // floor, so the building behind is seen from the street. The windows of a storey share their
  // sill and height, and the doors their height, as facades do (it also keeps the wall's grid of
  // cells, facade_wall_mesh's triangles, small).
  std::vector<Opening> openings(Random& rng, Millimetres length, Millimetres height) const {
    const Millimetres bay_target = to_mm(p_.bay_width), storey = to_mm(p_.storey_height);
    const Millimetres bays = std::max<Millimetres>(1, length / bay_target);
    const Millimetres storeys = std::max<Millimetres>(1, height / storey);
    const Millimetres door_top = std::min(storey, height) - kPier;
    const Millimetres door_height = draw_mm(rng, to_mm(p_.door_min_height), std::min(to_mm(p_.door_max_height), door_top));
    std::vector<Opening> out;
    bool ground_opening = false;
    auto across = [&](Millimetres b0, Millimetres b1, double lo, double hi, Opening& o) {
      const Millimetres room = b1 - b0 - 2 * kPier;
      const Millimetres w = draw_mm(rng, to_mm(lo), std::min(to_mm(hi), room));
      if (w > room) return false;  // does not fit this bay
      o.u0 = b0 + kPier + draw_mm(rng, Millimetres{0}, room - w), o.u1 = o.u0 + w;
      return true;
    };
    auto door = [&](Millimetres b0, Millimetres b1) {
      Opening o{0, 0, 0, door_height};
      if (door_height > door_top || !across(b0, b1, p_.door_min_width, p_.door_max_width, o)) return false;
      out.push_back(o);
      return true;
    };
    for (Millimetres s = 0; s < storeys; ++s) {
      const Millimetres floor = s * storey, top = std::min(floor + storey, height) - kPier;
      const Millimetres z0 = floor + to_mm(p_.sill_height);
      const Millimetres h = draw_mm(rng, to_mm(p_.window_min_height), std::min(to_mm(p_.window_max_height), top - z0));
      auto window = [&](Millimetres b0, Millimetres b1) {
        Opening o{0, z0, 0, z0 + h};
        if (z0 + h > top || !across(b0, b1, p_.window_min_width, p_.window_max_width, o)) return false;
        out.push_back(o);
        return true;
      };
      for (Millimetres k = 0; k < bays; ++k) {
        const Millimetres b0 = length * k / bays, b1 = length * (k + 1) / bays;
        if (s == 0 && rng.bernoulli(p_.door_fraction)) ground_opening |= door(b0, b1);
        else if (rng.bernoulli(p_.window_fraction)) ground_opening |= window(b0, b1) && s == 0;
      }
      if (s == 0 && !ground_opening) {
        // The middle bay's ground floor has no opening yet (none was drawn on the ground floor).
        const Millimetres k = bays / 2, b0 = length * k / bays, b1 = length * (k + 1) / bays;
        if (!door(b0, b1)) window(b0, b1);
      }
    }
    return out;
  }

  void facade(const PlanFrame& f, Millimetres length, Random& rng) {
    const Millimetres s = to_mm(p_.setback), depth = to_mm(p_.frontage_depth);
    const Millimetres thickness = draw_mm(rng, p_.wall_min_thickness, p_.wall_max_thickness);
    const Millimetres height = draw_mm(rng, p_.wall_min_height, p_.wall_max_height);
    const Millimetres wall_length = length - 2 * s;
    mesh(facade_wall_mesh(f, s, wall_length, thickness, height, openings(rng, wall_length, height)), "facade_wall");
    // The target: a low building right behind the wall, 1 m in from its ends, lower than its top.
    const Millimetres v0 = thickness + s;
    const Millimetres v1 = v0 + draw_mm(rng, Millimetres{1000}, depth - s - v0);
    building(f, s + 1000, v0, length - s - 1000, v1,
             draw_mm(rng, to_mm(p_.target_min_height), std::min(to_mm(p_.target_max_height), height - 500)));
  }

  void arcade(const PlanFrame& f, Millimetres length, Random& rng) {
    const Millimetres s = to_mm(p_.setback), depth = to_mm(p_.frontage_depth), column = to_mm(p_.column_size);
    const Millimetres clearance = draw_mm(rng, p_.arcade_min_clearance, p_.arcade_max_clearance);
    const Millimetres slab = draw_mm(rng, p_.arcade_min_slab, p_.arcade_max_slab);
    MeshObject m = box_mesh(f, s, 0, clearance, length - s, depth - s, clearance + slab);
    // Columns along the street edge, evenly from one end of the slab to the other.
    const Millimetres run = length - 2 * s - column;
    const Millimetres gaps = std::max<Millimetres>(1, run / to_mm(p_.column_spacing));
    for (Millimetres k = 0; k <= gaps; ++k) {
      const Millimetres u0 = s + run * k / gaps;
      append_part(m, box_mesh(f, u0, 0, 0, u0 + column, column, clearance));
    }
    mesh(std::move(m), "arcade");
    // A low building under the overhang, behind the columns.
    const Millimetres w = draw_mm(rng, Millimetres{2000}, std::min<Millimetres>(6000, length - 2 * s - 2000));
    const Millimetres u0 = s + 1000 + draw_mm(rng, Millimetres{0}, length - 2 * s - 2000 - w);
    building(f, u0, column + s, u0 + w, depth - 2 * s,
             draw_mm(rng, to_mm(p_.target_min_height), std::min(to_mm(p_.target_max_height), clearance - 500)));
  }

  void plain(const PlanFrame& f, Millimetres length, Random& rng) {
    const Millimetres s = to_mm(p_.setback), depth = to_mm(p_.frontage_depth);
    const Millimetres k = rng.uniform_int(1, 3);
    for (Millimetres i = 0; i < k; ++i) {
      const Millimetres q0 = s + (length - 2 * s) * i / k, q1 = s + (length - 2 * s) * (i + 1) / k;
      building(f, q0 + (i > 0 ? s : 0), s, q1 - (i + 1 < k ? s : 0), depth - s,
               draw_mm(rng, p_.min_height, p_.max_height));
    }
  }

  Scene build() {
    validate(p_);
    const ManhattanLayout layout = manhattan_layout(street_grid(p_));
    const Millimetres depth = to_mm(p_.frontage_depth), s = to_mm(p_.setback), side = layout.block;

    // Bridged streets first: they decide which street fronts stay empty.
    struct Bridge {
      int i, j;
      bool along_x;  // spans the street between block (i, j) and (i + 1, j); else (i, j) and (i, j + 1)
    };
    std::vector<Bridge> candidates;
    for (int j = 0; j < p_.blocks_y; ++j)
      for (int i = 0; i < p_.blocks_x; ++i) {
        if (i + 1 < p_.blocks_x) candidates.push_back({i, j, true});
        if (j + 1 < p_.blocks_y) candidates.push_back({i, j, false});
      }
    Random bridge_rng = Random::stream(seed_, kBridgeStream);
    const std::size_t bridges = std::min<std::size_t>(p_.bridge_count, candidates.size());
    for (std::size_t k = 0; k < bridges; ++k)  // partial Fisher-Yates shuffle
      std::swap(candidates[k], candidates[k + bridge_rng.uniform_int(0, static_cast<std::int64_t>(candidates.size() - k - 1))]);
    candidates.resize(bridges);
    // Fronts: 0 south, 1 east, 2 north, 3 west.
    auto landing = [&](int i, int j, int front) {
      return std::any_of(candidates.begin(), candidates.end(), [&](const Bridge& b) {
        if (b.along_x) return (b.i == i && b.j == j && front == 1) || (b.i + 1 == i && b.j == j && front == 3);
        return (b.i == i && b.j == j && front == 2) || (b.i == i && b.j + 1 == j && front == 0);
      });
    };

    for (int j = 0; j < p_.blocks_y; ++j)
      for (int i = 0; i < p_.blocks_x; ++i) {
        const MillimetreBox box = layout.block_box(i, j);
        Random rng = Random::stream(seed_, kOpeningsBlockStream, static_cast<std::uint64_t>(i), static_cast<std::uint64_t>(j));
        // The core's lots, then the corners (south-west, south-east, north-east, north-west).
        const MillimetreBox core{box.lo_x + depth, box.lo_y + depth, box.hi_x - depth, box.hi_y - depth};
        const PlanFrame plan{0, 0, 1, 0};
        for (const MillimetreBox& lot : lots_of_block(core, p_.core_buildings))
          building(plan, lot.lo_x + s, lot.lo_y + s, lot.hi_x - s, lot.hi_y - s, draw_mm(rng, p_.min_height, p_.max_height));
        for (auto [x, y] : {std::pair{box.lo_x, box.lo_y}, {box.hi_x - depth, box.lo_y}, {box.hi_x - depth, box.hi_y - depth},
                            {box.lo_x, box.hi_y - depth}})
          building(plan, x + s, y + s, x + depth - s, y + depth - s, draw_mm(rng, p_.min_height, p_.max_height));
        // The four street fronts, each in its own frame: u along the street, v into the block.
        const PlanFrame fronts[4] = {{box.lo_x + depth, box.lo_y, 1, 0},
                                     {box.hi_x, box.lo_y + depth, 0, 1},
                                     {box.hi_x - depth, box.hi_y, -1, 0},
                                     {box.lo_x, box.hi_y - depth, 0, -1}};
        const Millimetres length = side - 2 * depth;
        for (int front = 0; front < 4; ++front) {
          Random front_rng = Random::stream(seed_, kFrontStream, static_cast<std::uint64_t>(4 * i + front),
                                            static_cast<std::uint64_t>(j));
          const double pick = front_rng.uniform01() * (p_.facade_weight + p_.arcade_weight + p_.plain_weight);
          if (landing(i, j, front)) continue;
          if (pick < p_.facade_weight) facade(fronts[front], length, front_rng);
          else if (pick < p_.facade_weight + p_.arcade_weight) arcade(fronts[front], length, front_rng);
          else plain(fronts[front], length, front_rng);
        }
      }

    // Bridges: a deck from one block's core to the other's, across both (empty) fronts and the street.
    for (const Bridge& b : candidates) {
      const MillimetreBox from = layout.block_box(b.i, b.j);
      const MillimetreBox to = b.along_x ? layout.block_box(b.i + 1, b.j) : layout.block_box(b.i, b.j + 1);
      const Millimetres width = draw_mm(bridge_rng, p_.bridge_min_width, p_.bridge_max_width);
      const Millimetres z0 = draw_mm(bridge_rng, p_.bridge_min_height, p_.bridge_max_height);
      const Millimetres z1 = z0 + to_mm(p_.bridge_thickness);
      // Across the street: between the facing cores; along it: inside the fronts' span.
      const Millimetres a0 = depth + s, a1 = side - depth - s - width;
      const Millimetres offset = a0 + draw_mm(bridge_rng, Millimetres{0}, a1 - a0);
      const PlanFrame plan{0, 0, 1, 0};
      if (b.along_x)
        mesh(box_mesh(plan, from.hi_x - depth, from.lo_y + offset, z0, to.lo_x + depth, from.lo_y + offset + width, z1), "bridge");
      else
        mesh(box_mesh(plan, from.lo_x + offset, from.hi_y - depth, z0, from.lo_x + offset + width, to.lo_y + depth, z1), "bridge");
    }
    return std::move(scene_);
  }

 private:
  const OpeningsParams& p_;
  std::uint64_t seed_;
  Scene scene_;
  std::size_t next_id_ = 0;
};

}  // namespace

void validate(const OpeningsParams& p, const std::string& generator) {
  const ParamChecks check("generator", generator);
  check.in_range("blocks_x", p.blocks_x, 1, 1000);
  check.in_range("blocks_y", p.blocks_y, 1, 1000);
  check.in_range("street_width", p.street_width, 1.0, 1000.0);
  check.in_range("setback", p.setback, 0.01, 10.0);
  check.in_range("column_size", p.column_size, 0.05, 10.0);
  check.in_range("wall_min_thickness", p.wall_min_thickness, 0.01, 10.0);
  check.in_range("wall_max_thickness", p.wall_max_thickness, p.wall_min_thickness, 10.0);
  // The strip holds a wall, the target behind it (1 m deep at least) and the gaps around; or the
  // arcade's columns, the building under it and the gaps around.
  const double least_depth = std::max(p.wall_max_thickness + 2 * p.setback + 1.0, p.column_size + 3 * p.setback + 1.0);
  check.in_range("frontage_depth", p.frontage_depth, least_depth, 1000.0);
  check.in_range("core_buildings", p.core_buildings, 1, 1000);
  check.in_range("bay_width", p.bay_width, 0.5, 100.0);
  // A front must hold one bay, the bridges' widest deck, and the arcade's low building.
  const double least_front = std::max({p.bay_width + 2 * p.setback, p.bridge_max_width + 2 * p.setback, 4.0 + 2 * p.setback});
  check.in_range("block_size", p.block_size, 2 * p.frontage_depth + least_front, 10000.0);
  const Millimetres core = to_mm(p.block_size) - 2 * to_mm(p.frontage_depth);
  if (narrowest_lot_side(core, p.core_buildings) - 2 * to_mm(p.setback) < 1000)
    check.fail("core_buildings", std::to_string(p.core_buildings) + " lots leave buildings narrower than 1 m in a core " +
                                     ParamChecks::text(metres(core)) + " m wide");
  check.above("min_height", p.min_height, 0.0, kMaxHeight);
  check.in_range("max_height", p.max_height, p.min_height, kMaxHeight);
  for (auto [name, w] : {std::pair{"facade_weight", p.facade_weight}, {"arcade_weight", p.arcade_weight},
                         {"plain_weight", p.plain_weight}})
    check.in_range(name, w, 0.0, 1000.0);
  if (!(p.facade_weight + p.arcade_weight + p.plain_weight > 0.0))
    check.fail("plain_weight", "facade_weight, arcade_weight and plain_weight must not all be 0");
  check.in_range("storey_height", p.storey_height, 1.0, 100.0);
  check.in_range("sill_height", p.sill_height, 0.0, p.storey_height);
  check.in_range("door_min_width", p.door_min_width, 0.1, p.bay_width - 0.6);
  check.in_range("door_max_width", p.door_max_width, p.door_min_width, 100.0);
  check.in_range("door_min_height", p.door_min_height, 0.1, p.storey_height - 0.3);
  check.in_range("door_max_height", p.door_max_height, p.door_min_height, 100.0);
  check.in_range("window_min_width", p.window_min_width, 0.1, p.bay_width - 0.6);
  check.in_range("window_max_width", p.window_max_width, p.window_min_width, 100.0);
  check.in_range("window_min_height", p.window_min_height, 0.1, p.storey_height - p.sill_height - 0.3);
  check.in_range("window_max_height", p.window_max_height, p.window_min_height, 100.0);
  check.in_range("door_fraction", p.door_fraction, 0.0, 1.0);
  check.in_range("window_fraction", p.window_fraction, 0.0, 1.0);
  check.in_range("wall_min_height", p.wall_min_height, p.storey_height, kMaxHeight);
  check.in_range("wall_max_height", p.wall_max_height, p.wall_min_height, kMaxHeight);
  check.in_range("arcade_min_clearance", p.arcade_min_clearance, 1.0, kMaxHeight);
  check.in_range("arcade_max_clearance", p.arcade_max_clearance, p.arcade_min_clearance, kMaxHeight);
  check.in_range("arcade_min_slab", p.arcade_min_slab, 0.1, kMaxHeight);
  check.in_range("arcade_max_slab", p.arcade_max_slab, p.arcade_min_slab, kMaxHeight - p.arcade_max_clearance);
  check.in_range("column_spacing", p.column_spacing, p.column_size + 0.1, 1000.0);
  // The low building must stay 0.5 m below the wall's top and the arcade's slab.
  check.above("target_min_height", p.target_min_height, 0.0, std::min(p.wall_min_height, p.arcade_min_clearance) - 0.5);
  check.in_range("target_max_height", p.target_max_height, p.target_min_height, kMaxHeight);
  check.in_range("bridge_count", p.bridge_count, 0, 100000);
  check.in_range("bridge_min_height", p.bridge_min_height, 2.5, kMaxHeight);
  check.in_range("bridge_max_height", p.bridge_max_height, p.bridge_min_height, kMaxHeight - 100.0);
  check.in_range("bridge_thickness", p.bridge_thickness, 0.05, 100.0);
  check.in_range("bridge_min_width", p.bridge_min_width, 0.5, 1000.0);
  check.in_range("bridge_max_width", p.bridge_max_width, p.bridge_min_width, 1000.0);
}

Scene openings_city(const OpeningsParams& p, std::uint64_t seed) { return CityBuilder(p, seed).build(); }

}  // namespace cullcheck::generators
