// Table 3.3 of the thesis in kind (ch. 3.3.3): radar echo times over a terrain of the thesis's
// size (66 x 56 km, 4.96 million triangles) for regular grids of 30 x 30 to 400 x 400 cells, at
// 60 degrees (the thesis's coverage) and 360 degrees, by the published and the conservative
// rule, with the triangles each finds and tests, the oracle's witnessed count and what each rule
// misses; the same on a real elevation model when one is given (the Rainier tile); how the time
// grows with the terrain's size at a fixed grid; which grids meet the thesis's real-time bar (a
// rotation every 2 s, 360 degrees on one core); a moving platform (a rotation recomputed at each
// position of a drive across the terrain, against region echoes reused over stretches of it:
// reports/radar_platform.hpp); echo PNGs of one grid beside the report.
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "reports/radar_platform.hpp"

namespace cullcheck {

struct RadarTableOptions {
  std::vector<std::uint32_t> grids = {30, 60, 100, 200, 400};
  double height = 30.0;     // the transmitter's mast, metres above the ground at the terrain's centre
  int repeats = 5;          // timed echoes per rule and configuration
  std::uint64_t seed = 1;   // the generated terrain's
  std::string dem;          // a real elevation model measured the same way; empty: none
  std::vector<double> size_shares = {1.0 / 16, 1.0 / 4, 1.0};  // terrain-size scaling: shares of the thesis's area
  std::uint32_t scaling_grid = 100;
  int oracle_subdivisions = 1;  // oracle rays per triangle: n x n
  std::string echo_prefix;      // PREFIX_<terrain>_{oracle,thesis,conservative,diff_*}.png of the echo_grid 360° echo; empty: none
  std::uint32_t echo_grid = 100;
  int echo_size = 1024;
  double rotation_ms = 2000.0;
  // The moving platform on the generated terrain (reports/radar_platform.hpp; 0 positions:
  // none); its mast is `height`.
  PlatformOptions platform;
  // The built-in default city (2,808 buildings) standing on the thesis terrain's centre, the mast
  // in it: buildings on hills (core/terrain_scene.hpp).
  bool city = true;
};

// report.json's "radar_echo".
nlohmann::json radar_table_3_3(const RadarTableOptions& options);
std::string radar_table_3_3_text(const nlohmann::json& table);
// Witnessed triangles the conservative rule misses (the gate's share; the thesis's rule is the
// claims ledger's business).
std::uint64_t radar_table_violations(const nlohmann::json& table);

}  // namespace cullcheck
