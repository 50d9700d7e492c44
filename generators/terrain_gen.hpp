// Seeded generated terrains (core/terrain.hpp), deterministic like the cities: the same seed and
// parameters give the same heights, bit for bit, on any machine.
//
// Styles:
//   fractal   diamond-square midpoint displacement (Fournier, Fussell & Carpenter 1982) on the
//             smallest 2^k + 1 square covering the grid, cropped to it; `roughness` is the
//             factor each halving of the step multiplies the displacement by (0.5: smooth
//             hills, 0.7: rugged mountains)
//   ridged    the fractal field folded about its median (1 - |2u - 1|, squared): sharp ridges
//             and V-shaped valleys, the radar's hard case of long crests shadowing what is behind
//   terraces  the fractal field quantised to `steps` levels: flat benches joined by one-cell
//             cliffs (the steepest slope a height field holds)
//   flat      every vertex at `base` (an eye at that height sees the whole terrain edge-on)
// Heights span [base, base + relief] (flat: base alone). With `holes` > 0, each vertex is a hole
// (core/terrain.hpp: an elevation model's masked NoData) with that probability, drawn per vertex
// from the seed; at least one vertex stays filled.
//
// The thesis's test terrain (ch. 3.3: about 66 km x 56 km, about 4.96 million triangles) is
// `thesis_terrain_params()`: 1711 x 1451 vertices 38.6 m apart.
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>

#include "core/terrain.hpp"

namespace cullcheck::generators {

struct TerrainParams {
  int nx = 257;  // vertices east
  int ny = 257;  // vertices north
  double spacing = 30.0;  // metres between vertices, both ways
  std::string style = "fractal";
  double relief = 800.0;     // metres from the lowest to the highest vertex
  double base = 0.0;         // height of the lowest vertex
  double roughness = 0.55;   // fractal, ridged, terraces: displacement factor per halving
  int steps = 8;             // terraces: number of levels
  double holes = 0.0;        // share of vertices made NoData holes (seeded), in [0, 0.5]; 0: none

  template <class Self, class Visitor>
  static void visit(Self& s, Visitor&& v) {
    v("nx", s.nx), v("ny", s.ny), v("spacing", s.spacing), v("style", s.style), v("relief", s.relief);
    v("base", s.base), v("roughness", s.roughness), v("steps", s.steps), v("holes", s.holes);
  }
};

TerrainParams thesis_terrain_params();

// Throws InputError("terrain", field, ...) on parameters out of range (grids from 2 x 2 to
// 8193 x 8193 vertices, spacing in (0, 10 km], relief in [0, 20 km], roughness in (0, 1),
// steps in [2, 1000], a style not listed). The grid is centred on the local origin.
Terrain generate_terrain(const TerrainParams& params, std::uint64_t seed);

// `params` overlaid on the defaults (strictly: an unknown name is an InputError). A "preset"
// member names the defaults to start from: "default" (the values above) or "thesis".
TerrainParams terrain_params_from_json(const nlohmann::json& params);
nlohmann::json terrain_params_to_json(const TerrainParams& params);

}  // namespace cullcheck::generators
