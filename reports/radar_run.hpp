// One radar run (thesis ch. 3.3): a terrain (generated or read from an elevation model), a
// transmitter, a grid and a sector; the echo of each rule timed and held to the terrain oracle;
// JSON for report.json, a text table, echo PNGs and the replay command.
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "core/formats/dem_reader.hpp"
#include "core/terrain.hpp"
#include "core/terrain_scene.hpp"
#include "engine/radar/radar_echo.hpp"
#include "engine/radar/triangle_grid.hpp"
#include "oracle/terrain_oracle.hpp"
#include "reports/scene_source.hpp"

namespace cullcheck {

// Where the terrain comes from: an elevation model, or the terrain generator's parameters and
// seed (generators/terrain_gen.hpp).
struct TerrainSource {
  std::string dem;  // a file GDAL reads; empty: generated
  formats::DemOptions dem_options;
  nlohmann::json params = nlohmann::json::object();
  std::uint64_t seed = 1;
  // A city whose buildings stand on the terrain (core/terrain_scene.hpp); unset: the terrain alone.
  std::optional<SceneSource> city;

  // The terrain, and one line saying what was done to it (NoData filled or masked, resampling).
  Terrain load(std::string* summary = nullptr) const;
  // The terrain with the city's buildings standing on it (none without a city).
  TerrainScene load_scene(std::string* summary = nullptr) const;
  // Flags that rebuild it on the command line (each as `cullcheck radar` takes it).
  std::string replay_flags() const;
};

struct RadarRunOptions {
  std::optional<Vec2> at;         // transmitter's plan position; unset: the terrain's centre
  double height = 10.0;           // above the ground there (above the roof on a building), metres
  std::uint32_t grid_x = 100, grid_y = 100;
  radar::Sector sector;           // radians
  std::vector<std::string> rules = {"thesis", "conservative"};  // radar::named_rules() names
  int repeats = 5;                // timed echoes per rule: median and p95
  bool oracle = true;
  oracle::TerrainWitnessOptions witness;  // the sector is set from `sector`
  std::string echo_prefix;        // when set: PREFIX_<rule>.png, PREFIX_oracle.png, PREFIX_diff_<rule>.png
  int echo_size = 1024;           // pixels a side
  double range = 0.0;             // of the echo pictures, metres; 0: to the farthest terrain corner
  // A moving mast: the region echo (engine/radar/region_echo.hpp) for every position within this
  // radius of `at`, held to the oracle from the centre, `region_rim` points on the rim and as
  // many half-way out (reports/radar_region.hpp). 0: none.
  double region = 0.0;
  int region_rim = 8;
};

// {"terrain": {...}, "transmitter": {...}, "grid": [gx, gy], "sector_deg": [centre, width],
//  "rules": [{rule, claims_conservative, ms_median, ms_p95, visible, triangles_tested,
//             cells_tested, cells_visible, shadows, missed, first_missed, pvs_over_witnessed}],
//  "oracle": {witnessed, rays, ms, subdivisions}, "echo_files": [...], "replay": "...",
//  "region": {radius_m, z_m, ms, visible, samples, missed, centre_echo_missed, witnessed_union}}
// Throws InputError when the transmitter stands off the terrain or over a hole.
nlohmann::json radar_run(const TerrainScene& scene, const std::string& terrain_summary, const TerrainSource& source,
                         const RadarRunOptions& options);
std::string radar_table(const nlohmann::json& run);
// One rule's row of a run: its echo timed `repeats` times (median, p95), its counts, and against
// `seen` (when given) the witnessed triangles it misses and its PVS over the witnessed count.
nlohmann::json radar_rule_row(const radar::TriangleGrid& grid, const std::string& rule, Vec3 eye, const radar::Sector& sector, int repeats,
                              const oracle::TerrainWitness* seen, radar::Echo* echo = nullptr);
// Witnessed triangles some rule's PVS (or the region echo's) lacks, over all rules run (both claim conservative: the
// thesis says its rule "finds all visible primitives").
std::size_t radar_violations(const nlohmann::json& run);
std::string radar_replay_command(const TerrainSource& source, const RadarRunOptions& options, Vec2 at);

// `--rule`'s text: "both" (thesis and conservative), "all" (every named variant) or a comma-separated
// list of radar::named_rules() names; InputError naming the unknown one otherwise.
std::vector<std::string> parse_radar_rules(const std::string& text);

}  // namespace cullcheck
