// Generated terrains for the radar's properties (radar_test.cpp, radar_region_test.cpp): every
// style, 3 to 40 vertices a side, 1 to 90 m spacing, NoData holes in one case of `hole_odds`,
// and in one case of four a small Manhattan city standing on a terrain at least 130 m across.
// Drawn inside rc::gen::exec.
#pragma once

#include <rapidcheck.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>
#include <string>

#include "generators/terrain_gen.hpp"
#include "reports/scene_source.hpp"

namespace cullcheck {

struct TerrainCase {
  generators::TerrainParams params;
  std::uint64_t seed = 1;
  std::optional<SceneSource> city;
};

inline TerrainCase draw_terrain_case(int hole_odds) {
  TerrainCase c;
  c.params.style = *rc::gen::element<std::string>("fractal", "ridged", "terraces", "flat");
  c.params.nx = *rc::gen::inRange(3, 41);
  c.params.ny = *rc::gen::inRange(3, 41);
  c.params.spacing = *rc::gen::element(1.0, 7.5, 20.0, 30.0, 90.0);
  c.params.relief = c.params.style == "flat" ? 0.0 : *rc::gen::inRange(0, 400);
  c.params.base = *rc::gen::element(0.0, -30.0, 1200.0);
  c.params.roughness = *rc::gen::element(0.45, 0.55, 0.7);
  c.params.steps = *rc::gen::inRange(2, 9);
  c.params.holes = *rc::gen::weightedElement<double>({{hole_odds - 1, 0.0}, {1, 0.12}});
  if (*rc::gen::inRange(0, 4) == 0) {  // a small city on it: the terrain at least 130 m across, no holes
    SceneSource city;
    city.generator = "manhattan";
    city.seed = std::uint64_t(*rc::gen::inRange(1, 1000));
    city.parameters_json = nlohmann::json{{"blocks_x", *rc::gen::inRange(1, 3)}, {"blocks_y", *rc::gen::inRange(1, 3)},
                                          {"block_size", *rc::gen::element(20.0, 40.0)}, {"street_width", *rc::gen::element(6.0, 12.0)},
                                          {"buildings_per_block", *rc::gen::inRange(1, 5)}}
                               .dump();
    c.city = city;
    c.params.style = *rc::gen::element<std::string>("fractal", "ridged", "terraces");
    c.params.spacing = *rc::gen::element(7.5, 20.0, 30.0);
    const int need = int(std::ceil(130.0 / c.params.spacing)) + 1;
    c.params.nx = std::max(c.params.nx, need), c.params.ny = std::max(c.params.ny, need);
    c.params.relief = *rc::gen::inRange(0, 120);
    c.params.holes = 0.0;
  }
  c.seed = std::uint64_t(*rc::gen::inRange(1, 100000));
  return c;
}

}  // namespace cullcheck
