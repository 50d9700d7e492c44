#include "reports/radar_table.hpp"

#include <algorithm>
#include <chrono>
#include <iterator>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "core/elapsed.hpp"
#include "core/errors.hpp"
#include "engine/radar/triangle_grid.hpp"
#include "generators/terrain_gen.hpp"
#include "oracle/terrain_oracle.hpp"
#include "reports/echo_image.hpp"
#include "reports/radar_run.hpp"
#include "reports/statistics.hpp"

namespace cullcheck {
namespace {

using nlohmann::json;

const std::vector<std::string> kRules = {"thesis", "conservative"};
// The thesis's 60-degree coverage, centred on north; and the full circle.
const radar::Sector kSixty{kPi / 2, kPi / 3};
const radar::Sector kFull{};

json terrain_json(const Terrain& t, const std::string& name, const std::string& summary) {
  const Box3 b = t.bounds();
  return {{"name", name},
          {"summary", summary},
          {"vertices", {t.nx, t.ny}},
          {"spacing_m", {t.dx, t.dy}},
          {"extent_km", {(t.nx - 1) * t.dx / 1000, (t.ny - 1) * t.dy / 1000}},
          {"triangles", t.present_triangle_count()},
          {"height_range_m", {b.lo.z, b.hi.z}}};
}

// One terrain's rows: every grid, both sectors, both rules; the oracle once per sector.
json measure_terrain(const Terrain& terrain, const std::string& name, const std::string& summary, const TerrainSource& source,
                     const RadarTableOptions& o) {
  json out = terrain_json(terrain, name, summary);
  const Vec2 at = terrain.bounds().plan().center();
  const double ground = terrain.height_at(at);
  if (!std::isfinite(ground)) throw InputError("radar", "terrain", name + ": its centre is a NoData hole; fill NoData to measure it");
  const Vec3 eye{at.x, at.y, ground + o.height};
  out["transmitter"] = {{"at", {at.x, at.y}}, {"ground_m", ground}, {"height_m", o.height}};
  std::printf("radar: %s, %zu triangles\n", name.c_str(), terrain.present_triangle_count());
  std::fflush(stdout);

  const auto t_oracle = std::chrono::steady_clock::now();
  const oracle::TerrainOracle truth(terrain);
  const double build_ms = ms_since(t_oracle);
  std::vector<oracle::TerrainWitness> seen;
  out["oracle"] = json::array();
  for (const radar::Sector& s : {kSixty, kFull}) {
    oracle::TerrainWitnessOptions w;
    w.subdivisions = o.oracle_subdivisions;
    w.sector_centre = s.centre, w.sector_width = s.width;
    const auto t0 = std::chrono::steady_clock::now();
    seen.push_back(truth.witnessed(eye, w));
    out["oracle"].push_back({{"sector_deg", s.width < kTwoPi ? 60 : 360},
                             {"witnessed", seen.back().witnessed.size()},
                             {"rays", seen.back().rays},
                             {"ms", ms_since(t0)},
                             {"embree_build_ms", build_ms},
                             {"subdivisions", o.oracle_subdivisions}});
  }
  out["rows"] = json::array();
  for (const std::uint32_t g : o.grids) {
    const auto t0 = std::chrono::steady_clock::now();
    const radar::TriangleGrid grid(terrain, g, g);
    const double grid_ms = ms_since(t0);
    for (int k = 0; k < 2; ++k) {
      const radar::Sector& s = k == 0 ? kSixty : kFull;
      json row = {{"grid", g}, {"grid_build_ms", grid_ms}, {"references", grid.references()}, {"sector_deg", k == 0 ? 60 : 360}};
      row["rules"] = json::array();
      for (const std::string& rule : kRules) {
        radar::Echo echo;
        row["rules"].push_back(radar_rule_row(grid, rule, eye, s, o.repeats, &seen[std::size_t(k)], &echo));
        if (k == 1 && g == o.echo_grid && !o.echo_prefix.empty()) {
          const std::string prefix = o.echo_prefix + "_" + name;
          const double range = length(terrain.bounds().plan().hi - at) * 1.0;
          write_png(echo_image(terrain, echo.visible, eye, range, o.echo_size), prefix + "_" + rule + ".png");
          write_png(echo_difference_image(terrain, echo.visible, seen[1].witnessed, eye, range, o.echo_size), prefix + "_diff_" + rule + ".png");
          if (rule == kRules.back()) write_png(echo_image(terrain, seen[1].witnessed, eye, range, o.echo_size), prefix + "_oracle.png");
          out["echo_files"].push_back(prefix + "_" + rule + ".png");
          out["echo_files"].push_back(prefix + "_diff_" + rule + ".png");
          if (rule == kRules.back()) out["echo_files"].push_back(prefix + "_oracle.png");
        }
      }
      std::printf("radar: %s grid %u, %d deg: thesis %.1f ms, conservative %.1f ms\n", name.c_str(), g, k == 0 ? 60 : 360,
                  row["rules"][0]["ms_median"].get<double>(), row["rules"][1]["ms_median"].get<double>());
      std::fflush(stdout);
      out["rows"].push_back(row);
    }
  }
  RadarRunOptions replay;
  replay.height = o.height;
  replay.grid_x = replay.grid_y = o.echo_grid;
  out["replay"] = radar_replay_command(source, replay, at);
  return out;
}

}  // namespace

json radar_table_3_3(const RadarTableOptions& o) {
  if (o.grids.empty()) throw InputError("radar", "grids", "no grid size given");
  for (std::uint32_t g : o.grids)
    if (g == 0 || g > 4096) throw InputError("radar", "grids", std::to_string(g) + " is not a grid size in [1, 4096]");
  if (!(o.height >= 0.0) || !std::isfinite(o.height)) throw InputError("radar", "height", "must be a finite height above ground, 0 or more");
  json out;
  out["thesis_ms_60deg"] = {{"30", 266}, {"60", 214}, {"100", 209}, {"200", 333}, {"400", 898}};
  out["thesis_machine"] = "Pentium IV 3 GHz, GeForce4 MX 400 (Table 3.3: 60 degrees of coverage)";
  out["rotation_bar_ms"] = o.rotation_ms;
  out["height_m"] = o.height;
  out["terrains"] = json::array();

  TerrainSource generated;
  generated.params = {{"preset", "thesis"}};
  generated.seed = o.seed;
  std::string summary;
  // Each terrain timed as it loads (generated, or read from the elevation model), then measured;
  // the generated one is kept for the city and the moving platform.
  const auto measure = [&](const TerrainSource& source, const std::string& name, const char* load_key) {
    const auto t0 = std::chrono::steady_clock::now();
    Terrain terrain = source.load(&summary);
    const double load_ms = ms_since(t0);
    json t = measure_terrain(terrain, name, summary, source, o);
    t[load_key] = load_ms;
    out["terrains"].push_back(std::move(t));
    return terrain;
  };
  const Terrain thesis = measure(generated, "generated", "generate_ms");
  const std::string thesis_summary = summary;
  if (!o.dem.empty()) {
    TerrainSource real;
    real.dem = o.dem;
    measure(real, "dem", "load_ms");
  }

  if (o.city) {
    TerrainSource with_city = generated;
    with_city.city = SceneSource{};  // the built-in default city
    const auto t0 = std::chrono::steady_clock::now();
    const TerrainScene scene = stand_on_terrain(thesis, with_city.city->load(), with_city.city->replay_flags());
    summary = thesis_summary + "; " + std::to_string(scene.buildings.size()) + " buildings standing on it (" + with_city.city->replay_flags() + ")";
    const double load_ms = ms_since(t0);
    const radar::RadarSurface surface(scene);
    const Vec2 at = scene.terrain.bounds().plan().center();
    const Vec3 eye{at.x, at.y, standing_height(scene, at) + o.height};
    const auto t1 = std::chrono::steady_clock::now();
    const oracle::TerrainOracle truth(scene);
    oracle::TerrainWitnessOptions w;
    w.subdivisions = o.oracle_subdivisions;
    const oracle::TerrainWitness seen = truth.witnessed(eye, w);
    const double oracle_ms = ms_since(t1);
    const auto t2 = std::chrono::steady_clock::now();
    const radar::TriangleGrid grid(surface, o.echo_grid, o.echo_grid);
    json row = {{"summary", summary},
                {"buildings", scene.buildings.size()},
                {"building_triangles", surface.triangle_count() - surface.terrain_triangles()},
                {"triangles", surface.present_triangle_count()},
                {"load_ms", load_ms},
                {"grid", o.echo_grid},
                {"grid_build_ms", ms_since(t2)},
                {"transmitter_z_m", eye.z},
                {"on_building", building_at(scene, at) >= 0},
                {"oracle", {{"witnessed", seen.witnessed.size()}, {"rays", seen.rays}, {"ms", oracle_ms}}},
                {"sector_deg", 360}};
    std::size_t building_witnessed = 0;
    for (std::uint32_t t : seen.witnessed) building_witnessed += t >= surface.terrain_triangles();
    row["oracle"]["building_triangles_witnessed"] = building_witnessed;
    row["rules"] = json::array();
    // Pictures of the city's neighbourhood, 3 km a side.
    for (const std::string& rule : kRules) {
      radar::Echo echo;
      row["rules"].push_back(radar_rule_row(grid, rule, eye, kFull, o.repeats, &seen, &echo));
      if (o.echo_prefix.empty()) continue;
      const std::string prefix = o.echo_prefix + "_city";
      write_png(echo_image(scene, echo.visible, eye, 1500.0, o.echo_size), prefix + "_" + rule + ".png");
      write_png(echo_difference_image(scene, echo.visible, seen.witnessed, eye, 1500.0, o.echo_size), prefix + "_diff_" + rule + ".png");
      row["echo_files"].push_back(prefix + "_" + rule + ".png");
      row["echo_files"].push_back(prefix + "_diff_" + rule + ".png");
    }
    if (!o.echo_prefix.empty()) {
      write_png(echo_image(scene, seen.witnessed, eye, 1500.0, o.echo_size), o.echo_prefix + "_city_oracle.png");
      row["echo_files"].push_back(o.echo_prefix + "_city_oracle.png");
    }
    RadarRunOptions replay;
    replay.height = o.height;
    replay.grid_x = replay.grid_y = o.echo_grid;
    row["replay"] = radar_replay_command(with_city, replay, at);
    out["city_on_terrain"] = row;
  }

  // Growth with the terrain's size: the thesis terrain's generator over shares of its area, one grid.
  out["size_scaling"] = json::array();
  for (const double share : o.size_shares) {
    generators::TerrainParams p = generators::thesis_terrain_params();
    p.nx = std::max(2, int(std::lround((p.nx - 1) * std::sqrt(share))) + 1);
    p.ny = std::max(2, int(std::lround((p.ny - 1) * std::sqrt(share))) + 1);
    const Terrain t = generators::generate_terrain(p, o.seed);
    const Vec2 at = t.bounds().plan().center();
    const Vec3 eye{at.x, at.y, t.height_at(at) + o.height};
    const auto t0 = std::chrono::steady_clock::now();
    const radar::TriangleGrid grid(t, o.scaling_grid, o.scaling_grid);
    json row = {{"triangles", t.present_triangle_count()}, {"grid", o.scaling_grid}, {"grid_build_ms", ms_since(t0)}, {"sector_deg", 360}};
    row["rules"] = json::array();
    for (const std::string& rule : kRules) row["rules"].push_back(radar_rule_row(grid, rule, eye, kFull, o.repeats, nullptr));
    out["size_scaling"].push_back(row);
  }

  if (o.platform.positions > 0) {
    PlatformOptions p = o.platform;
    p.height = o.height;
    p.oracle_subdivisions = o.oracle_subdivisions;
    std::printf("radar: the moving platform\n");
    std::fflush(stdout);
    out["moving_platform"] = radar_moving_platform(thesis, p);
  }

  // The real-time bar: which grids echo 360 degrees within a rotation, rule by rule, terrain by terrain.
  out["meets_rotation_bar"] = json::array();
  for (const json& t : out["terrains"])
    for (const json& row : t["rows"]) {
      if (row["sector_deg"] != 360) continue;
      for (const json& r : row["rules"])
        if (r["ms_median"].get<double>() <= o.rotation_ms)
          out["meets_rotation_bar"].push_back({{"terrain", t["name"]}, {"grid", row["grid"]}, {"rule", r["rule"]}});
    }
  return out;
}

std::string radar_table_3_3_text(const json& table) {
  std::ostringstream s;
  char line[320];
  for (const json& t : table["terrains"]) {
    s << "radar echo (Table 3.3 in kind): " << t["summary"].get<std::string>() << "\n";
    std::snprintf(line, sizeof line, "  %zu triangles, %.1f x %.1f km; transmitter %.0f m above ground at the centre; oracle witnessed %zu (60 deg), %zu (360 deg)\n",
                  t["triangles"].get<std::size_t>(), t["extent_km"][0].get<double>(), t["extent_km"][1].get<double>(),
                  t["transmitter"]["height_m"].get<double>(), t["oracle"][0]["witnessed"].get<std::size_t>(),
                  t["oracle"][1]["witnessed"].get<std::size_t>());
    s << line;
    s << "  grid     deg  rule            ms_med     ms_p95    visible     tested   missed  pvs/witnessed  thesis_ms\n";
    for (const json& row : t["rows"])
      for (const json& r : row["rules"]) {
        const std::string g = std::to_string(row["grid"].get<std::uint32_t>());
        const bool thesis_row = t["name"] == "generated" && row["sector_deg"] == 60 && r["rule"] == "thesis" && table["thesis_ms_60deg"].contains(g);
        std::snprintf(line, sizeof line, "  %-7s %4d  %-13s %9.1f %10.1f %10zu %10zu %8zu %14.3f  %s\n", (g + "x" + g).c_str(),
                      row["sector_deg"].get<int>(), r["rule"].get<std::string>().c_str(), r["ms_median"].get<double>(),
                      r["ms_p95"].get<double>(), r["visible"].get<std::size_t>(), r["triangles_tested"].get<std::size_t>(),
                      r["missed"].get<std::size_t>(), r["pvs_over_witnessed"].get<double>(),
                      thesis_row ? std::to_string(table["thesis_ms_60deg"][g].get<int>()).c_str() : "");
        s << line;
      }
  }
  if (table.contains("city_on_terrain")) {
    const json& c = table["city_on_terrain"];
    std::snprintf(line, sizeof line, "  the default city on it: %zu buildings (%zu triangles), grid %u, 360 deg; oracle witnessed %zu (%zu of buildings)\n",
                  c["buildings"].get<std::size_t>(), c["building_triangles"].get<std::size_t>(), c["grid"].get<std::uint32_t>(),
                  c["oracle"]["witnessed"].get<std::size_t>(), c["oracle"]["building_triangles_witnessed"].get<std::size_t>());
    s << line;
    for (const json& r : c["rules"]) {
      std::snprintf(line, sizeof line, "    %-13s %9.1f ms median, %zu visible, %zu missed, PVS / witnessed %.3f\n", r["rule"].get<std::string>().c_str(),
                    r["ms_median"].get<double>(), r["visible"].get<std::size_t>(), r["missed"].get<std::size_t>(),
                    r["pvs_over_witnessed"].get<double>());
      s << line;
    }
  }
  s << "  size scaling (360 deg):\n";
  for (const json& row : table["size_scaling"]) {
    std::snprintf(line, sizeof line, "    %9zu triangles, grid %u: thesis %.1f ms, conservative %.1f ms\n", row["triangles"].get<std::size_t>(),
                  row["grid"].get<std::uint32_t>(), row["rules"][0]["ms_median"].get<double>(), row["rules"][1]["ms_median"].get<double>());
    s << line;
  }
  if (table.contains("moving_platform")) s << radar_moving_platform_text(table["moving_platform"]);
  s << "  within a 2 s rotation at 360 deg:";
  for (const json& m : table["meets_rotation_bar"])
    s << " " << m["terrain"].get<std::string>() << "/" << m["grid"].get<std::uint32_t>() << "/" << m["rule"].get<std::string>();
  s << "\n";
  return s.str();
}

std::uint64_t radar_table_violations(const json& table) {
  std::uint64_t n = 0;
  for (const json& t : table["terrains"])
    for (const json& row : t["rows"])
      for (const json& r : row["rules"])
        if (r["rule"] == "conservative") n += r["missed"].get<std::uint64_t>();
  if (table.contains("city_on_terrain"))
    for (const json& r : table["city_on_terrain"]["rules"])
      if (r["rule"] == "conservative") n += r["missed"].get<std::uint64_t>();
  if (table.contains("moving_platform")) {
    n += table["moving_platform"]["missed"].get<std::uint64_t>();
    for (const json& r : table["moving_platform"]["regions"]) n += r["missed"].get<std::uint64_t>();
  }
  return n;
}

}  // namespace cullcheck
