// The thesis testbed (ch. 3.2): 160,000 buildings of 46 triangles, 7.36 M triangles in all.
//
// Speed matters (it is generated in tests and benchmarks): every footprint is the same convex
// 16-gon translated by whole millimetres, so there is no trigonometry, no partition (convex
// footprints become one CVP directly) and one random draw per building.
#include <nlohmann/json.hpp>

#include "core/scene_io.hpp"
#include "generators/city.hpp"
#include "generators/footprint_shapes.hpp"
#include "generators/param_checks.hpp"
#include "generators/params_json.hpp"
#include "generators/random.hpp"

namespace cullcheck::generators {
namespace {

constexpr std::uint64_t kThesisStream = 0x54484553;  // "THES"

// Low edge of building i along one axis: buildings_per_block_side buildings with `gap` between
// them form a block; blocks are separated by streets instead of gaps.
Millimetres building_offset(int i, Millimetres size, Millimetres gap, Millimetres street, int per_block) {
  return i * (size + gap) + (i / per_block) * (street - gap);
}

}  // namespace

void validate(const ThesisParams& p, const std::string& generator) {
  const ParamChecks check("generator", generator);
  check.in_range("grid_x", p.grid_x, 1, 20000);
  check.in_range("grid_y", p.grid_y, 1, 20000);
  if (1LL * p.grid_x * p.grid_y > static_cast<long long>(kMaxBuildings))
    check.fail("grid_y", "grid_x * grid_y exceeds the scene limit of 20,000,000 buildings");
  check.in_range("building_size", p.building_size, 0.1, 10000.0);
  check.in_range("building_gap", p.building_gap, 0.01, 10000.0);
  check.in_range("buildings_per_block_side", p.buildings_per_block_side, 1, 20000);
  check.in_range("street_width", p.street_width, 0.01, 10000.0);
  // Four distinct rounded corners need straight sides left between them, and the Pythagorean
  // corner points stay convex after rounding to 1 mm only for radii of a few centimetres or more.
  check.in_range("corner_radius", p.corner_radius, 0.05, (p.building_size - 0.01) / 2);
  check.above("min_height", p.min_height, 0.0, kMaxHeight);
  check.in_range("max_height", p.max_height, p.min_height, kMaxHeight);
}

Scene thesis_city(const ThesisParams& p, std::uint64_t seed) {
  validate(p);
  Scene scene;
  scene.provenance = {"thesis", seed, params_to_json(p).dump()};
  const Millimetres size = to_mm(p.building_size), gap = to_mm(p.building_gap), street = to_mm(p.street_width);
  const Millimetres radius = to_mm(p.corner_radius);
  const Millimetres span_x = building_offset(p.grid_x - 1, size, gap, street, p.buildings_per_block_side) + size;
  const Millimetres span_y = building_offset(p.grid_y - 1, size, gap, street, p.buildings_per_block_side) + size;
  const Millimetres x0 = -(span_x / 2), y0 = -(span_y / 2);  // centred on the origin
  const Millimetres min_h = to_mm(p.min_height), max_h = to_mm(p.max_height);
  Random rng = Random::stream(seed, kThesisStream);
  scene.buildings.reserve(static_cast<std::size_t>(p.grid_x) * p.grid_y);
  for (int j = 0; j < p.grid_y; ++j) {
    const Millimetres y = y0 + building_offset(j, size, gap, street, p.buildings_per_block_side);
    for (int i = 0; i < p.grid_x; ++i) {
      const Millimetres x = x0 + building_offset(i, size, gap, street, p.buildings_per_block_side);
      Building b;
      b.id = static_cast<ObjectId>(scene.buildings.size());
      b.footprint = rounded_rectangle16(x, y, x + size, y + size, radius);
      b.height = metres(rng.uniform_int(min_h, max_h));
      validate_and_finish(b);
      scene.buildings.push_back(std::move(b));
    }
  }
  return scene;
}

}  // namespace cullcheck::generators
