#include "reports/radar_run.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iterator>
#include <sstream>

#include "core/elapsed.hpp"
#include "core/errors.hpp"
#include "core/replay_text.hpp"
#include "core/sorted_sets.hpp"
#include "engine/radar/triangle_grid.hpp"
#include "generators/terrain_gen.hpp"
#include "reports/echo_image.hpp"
#include "reports/radar_region.hpp"
#include "reports/statistics.hpp"

namespace cullcheck {
namespace {

double degrees(double radians) { return radians * 180.0 / kPi; }

bool full_circle(const radar::Sector& s) { return !(s.width < kTwoPi); }

}  // namespace

std::vector<std::string> parse_radar_rules(const std::string& text) {
  if (text == "both") return {"thesis", "conservative"};
  std::vector<std::string> out;
  if (text == "all") {
    for (const radar::NamedRules& n : radar::named_rules()) out.push_back(n.name);
    return out;
  }
  std::stringstream s(text);
  std::string name;
  while (std::getline(s, name, ',')) {
    if (!radar::rules_named(name)) {
      std::string known;
      for (const radar::NamedRules& n : radar::named_rules()) known += (known.empty() ? "" : ", ") + n.name;
      throw InputError("radar", "rule", "'" + name + "' is none of both, all, " + known);
    }
    out.push_back(name);
  }
  if (out.empty()) throw InputError("radar", "rule", "names no rule");
  return out;
}

Terrain TerrainSource::load(std::string* summary) const {
  if (!dem.empty()) {
    formats::DemImport d = formats::read_dem(dem, dem_options);
    if (summary) *summary = d.summary();
    return std::move(d.terrain);
  }
  Terrain t = generators::generate_terrain(generators::terrain_params_from_json(params), seed);
  if (summary) *summary = t.source;
  return t;
}

TerrainScene TerrainSource::load_scene(std::string* summary) const {
  Terrain terrain = load(summary);
  if (!city) return stand_on_terrain(std::move(terrain), Scene{});
  const Scene scene = city->load();
  TerrainScene out = stand_on_terrain(std::move(terrain), scene, city->replay_flags());
  if (summary) *summary += "; " + std::to_string(out.buildings.size()) + " buildings standing on it (" + city->replay_flags() + ")";
  return out;
}

std::string TerrainSource::replay_flags() const {
  std::ostringstream s;
  const std::string with_city = city ? " --with-city " + city->replay_flags() : "";
  if (dem.empty()) {
    s << "--terrain-params " << shell_quote(params.dump()) << " --terrain-seed " << seed << with_city;
    return s.str();
  }
  s << "--dem " << shell_quote(dem);
  const formats::DemOptions& o = dem_options;
  if (o.column || o.row || o.columns || o.rows) s << " --dem-window " << o.column << "," << o.row << "," << o.columns << "," << o.rows;
  if (o.step != 1) s << " --dem-step " << o.step;
  if (o.nodata == formats::NoData::mask) s << " --dem-nodata mask";
  if (!o.crs.empty()) s << " --dem-crs " << shell_quote(o.crs);
  s << with_city;
  return s.str();
}

std::string radar_replay_command(const TerrainSource& source, const RadarRunOptions& o, Vec2 at) {
  std::ostringstream s;
  s << "cullcheck radar " << source.replay_flags() << " --at " << round_trip_text(at.x) << "," << round_trip_text(at.y)
    << " --height " << round_trip_text(o.height) << " --grid " << o.grid_x << "," << o.grid_y;
  if (!full_circle(o.sector)) s << " --sector " << round_trip_text(degrees(o.sector.centre)) << "," << round_trip_text(degrees(o.sector.width));
  if (o.rules != RadarRunOptions{}.rules) {
    std::string list;
    for (const std::string& r : o.rules) list += (list.empty() ? "" : ",") + r;
    s << " --rule " << list;
  }
  if (o.witness.subdivisions != oracle::TerrainWitnessOptions{}.subdivisions) s << " --oracle-subdivisions " << o.witness.subdivisions;
  if (o.region > 0.0) s << " --region " << round_trip_text(o.region) << " --region-rim " << o.region_rim;
  return s.str();
}

nlohmann::json radar_rule_row(const radar::TriangleGrid& grid, const std::string& rule, Vec3 eye, const radar::Sector& sector, int repeats,
                              const oracle::TerrainWitness* seen, radar::Echo* echo_out) {
  const auto rules = radar::rules_named(rule);
  if (!rules) throw InputError("radar", "rule", "'" + rule + "' names no rule");
  radar::RadarEcho echo(grid, *rules);
  std::vector<double> ms;
  radar::Echo result;
  for (int r = 0; r < std::max(1, repeats); ++r) {
    const auto t0 = std::chrono::steady_clock::now();
    result = echo.compute(eye, sector);
    ms.push_back(ms_since(t0));
  }
  nlohmann::json row = {{"rule", rule},
                        {"claims_conservative", true},
                        {"ms_median", median(ms)},
                        {"ms_p95", percentile(ms, 95)},
                        {"repeats", ms.size()},
                        {"visible", result.visible.size()},
                        {"triangles_tested", result.stats.triangles_tested},
                        {"cells_tested", result.stats.cells_tested},
                        {"cells_visible", result.stats.cells_visible},
                        {"shadows", result.stats.shadows}};
  if (seen) {
    const std::vector<std::uint32_t> missed = missing(seen->witnessed, result.visible);
    row["missed"] = missed.size();
    row["pvs_over_witnessed"] = seen->witnessed.empty() ? 0.0 : double(result.visible.size()) / double(seen->witnessed.size());
    if (!missed.empty()) {
      const auto k = std::lower_bound(seen->witnessed.begin(), seen->witnessed.end(), missed[0]) - seen->witnessed.begin();
      const Vec3 q = seen->witness_points[std::size_t(k)];
      row["first_missed"] = {{"triangle", missed[0]}, {"witness_point", {q.x, q.y, q.z}}};
    }
  }
  if (echo_out) *echo_out = std::move(result);
  return row;
}

nlohmann::json radar_run(const TerrainScene& scene, const std::string& summary, const TerrainSource& source, const RadarRunOptions& o) {
  const Terrain& terrain = scene.terrain;
  const Box3 bounds = terrain.bounds();
  const Vec2 at = o.at ? *o.at : bounds.plan().center();
  // The ground, or on a building its roof (a mast on the roof).
  const double ground = standing_height(scene, at);
  if (!std::isfinite(ground))
    throw InputError("transmitter", "at", "(" + round_trip_text(at.x) + ", " + round_trip_text(at.y) + ") is off the terrain or over a NoData hole");
  const std::int64_t on = building_at(scene, at);
  if (!(o.height >= 0.0) || !std::isfinite(o.height)) throw InputError("transmitter", "height", "must be a finite height above ground, 0 or more");
  if (o.grid_x == 0 || o.grid_y == 0 || o.grid_x > 4096 || o.grid_y > 4096)
    throw InputError("radar", "grid", "cells each way must lie in [1, 4096]");
  if (!(o.sector.width > 0.0)) throw InputError("radar", "sector", "its width must be positive");
  const Vec3 eye{at.x, at.y, ground + o.height};

  nlohmann::json out;
  out["terrain"] = {{"source", terrain.source},
                    {"summary", summary},
                    {"vertices", {terrain.nx, terrain.ny}},
                    {"spacing_m", {terrain.dx, terrain.dy}},
                    {"extent_m", {(terrain.nx - 1) * terrain.dx, (terrain.ny - 1) * terrain.dy}},
                    {"triangles", terrain.present_triangle_count()},
                    {"height_range_m", {bounds.lo.z, bounds.hi.z}}};
  out["transmitter"] = {{"at", {at.x, at.y}}, {"ground_m", ground}, {"height_m", o.height}, {"z_m", eye.z}};
  if (on >= 0) out["transmitter"]["on_building"] = scene.buildings[std::size_t(on)].id;
  radar::RadarSurface surface(scene);
  out["buildings"] = {{"count", scene.buildings.size()}, {"triangles", surface.triangle_count() - surface.terrain_triangles()},
                      {"city", scene.city}};
  out["grid"] = {o.grid_x, o.grid_y};
  out["sector_deg"] = {degrees(o.sector.centre), full_circle(o.sector) ? 360.0 : degrees(o.sector.width)};

  const auto t_grid = std::chrono::steady_clock::now();
  const radar::TriangleGrid grid(surface, o.grid_x, o.grid_y);
  out["grid_build_ms"] = ms_since(t_grid);
  out["grid_references"] = grid.references();

  oracle::TerrainWitness seen;
  if (o.oracle) {
    const auto t0 = std::chrono::steady_clock::now();
    const oracle::TerrainOracle truth(scene);
    oracle::TerrainWitnessOptions w = o.witness;
    w.sector_centre = o.sector.centre;
    w.sector_width = o.sector.width;
    seen = truth.witnessed(eye, w);
    out["oracle"] = {{"witnessed", seen.witnessed.size()}, {"rays", seen.rays}, {"ms", ms_since(t0)}, {"subdivisions", w.subdivisions}};
  }
  double range = o.range;
  if (!(range > 0.0))
    for (const Vec2 c : {bounds.plan().lo, bounds.plan().hi, Vec2{bounds.lo.x, bounds.hi.y}, Vec2{bounds.hi.x, bounds.lo.y}})
      range = std::max(range, length(c - at));
  std::vector<std::string> files;
  const auto picture = [&](const RgbImage& image, const std::string& what) {
    const std::string path = o.echo_prefix + "_" + what + ".png";
    write_png(image, path);
    files.push_back(path);
  };
  if (!o.echo_prefix.empty() && o.oracle) picture(echo_image(scene, seen.witnessed, eye, range, o.echo_size), "oracle");

  out["rules"] = nlohmann::json::array();
  for (const std::string& name : o.rules) {
    radar::Echo result;
    nlohmann::json row = radar_rule_row(grid, name, eye, o.sector, o.repeats, o.oracle ? &seen : nullptr, &result);
    if (o.oracle && !o.echo_prefix.empty())
      picture(echo_difference_image(scene, result.visible, seen.witnessed, eye, range, o.echo_size), "diff_" + name);
    if (!o.echo_prefix.empty()) picture(echo_image(scene, result.visible, eye, range, o.echo_size), name);
    out["rules"].push_back(row);
  }
  if (o.region > 0.0) {
    if (!o.oracle) throw InputError("radar", "region", "is checked by the oracle: drop --no-oracle");
    const oracle::TerrainOracle truth(scene);
    const auto t0 = std::chrono::steady_clock::now();
    const RegionCheck c = check_region_echo(scene, grid, truth, at, o.region, o.height, o.region_rim, o.sector, o.witness);
    const radar::MastRegion r = mast_region(scene, at, o.region, o.height);
    out["region"] = {{"radius_m", o.region},
                     {"z_m", {r.z_low, r.z_high}},
                     {"check_ms", ms_since(t0)},
                     {"visible", c.echo.visible.size()},
                     {"triangles_tested", c.echo.stats.triangles_tested},
                     {"samples", c.samples},
                     {"missed", c.missed},
                     {"centre_echo_missed", c.centre_echo_missed},
                     {"witnessed_union", c.witnessed_union}};
    if (!c.first_missed.empty()) out["region"]["first_missed"] = c.first_missed;
  }
  out["echo_range_m"] = range;
  out["echo_files"] = files;
  out["replay"] = radar_replay_command(source, o, at);
  return out;
}

std::string radar_table(const nlohmann::json& run) {
  std::ostringstream s;
  s.setf(std::ios::fixed);
  s.precision(3);
  const auto& t = run["terrain"];
  s << "terrain: " << t["summary"].get<std::string>() << "\n";
  s << "  " << t["triangles"].get<std::size_t>() << " triangles, " << t["extent_m"][0].get<double>() / 1000 << " x "
    << t["extent_m"][1].get<double>() / 1000 << " km; transmitter " << run["transmitter"]["height_m"].get<double>()
    << " m above ground at (" << run["transmitter"]["at"][0].get<double>() << ", " << run["transmitter"]["at"][1].get<double>()
    << "); grid " << run["grid"][0] << " x " << run["grid"][1] << "; sector " << run["sector_deg"][1].get<double>() << " deg\n";
  if (run.contains("oracle"))
    s << "oracle: " << run["oracle"]["witnessed"] << " triangles witnessed by " << run["oracle"]["rays"] << " rays\n";
  s << "rule                      ms_med    ms_p95    visible    tested  cells_vis/tested   missed  pvs/witnessed\n";
  for (const auto& r : run["rules"]) {
    char line[256];
    std::snprintf(line, sizeof line, "%-22s %9.3f %9.3f %10zu %9zu %8zu/%-8zu %8s %14s\n", r["rule"].get<std::string>().c_str(),
                  r["ms_median"].get<double>(), r["ms_p95"].get<double>(), r["visible"].get<std::size_t>(),
                  r["triangles_tested"].get<std::size_t>(), r["cells_visible"].get<std::size_t>(), r["cells_tested"].get<std::size_t>(),
                  r.contains("missed") ? std::to_string(r["missed"].get<std::size_t>()).c_str() : "-",
                  r.contains("pvs_over_witnessed") ? std::to_string(r["pvs_over_witnessed"].get<double>()).substr(0, 6).c_str() : "-");
    s << line;
  }
  if (run.contains("region")) {
    const auto& r = run["region"];
    char line[320];
    std::snprintf(line, sizeof line,
                  "region echo (a mast anywhere within %.1f m, eye %.1f to %.1f m): %zu visible; from %zu sample positions the oracle "
                  "witnessed %zu triangles in all, %zu missed (the centre's own conservative echo would miss %zu)\n",
                  r["radius_m"].get<double>(), r["z_m"][0].get<double>(), r["z_m"][1].get<double>(), r["visible"].get<std::size_t>(),
                  r["samples"].get<std::size_t>(), r["witnessed_union"].get<std::size_t>(), r["missed"].get<std::size_t>(),
                  r["centre_echo_missed"].get<std::size_t>());
    s << line;
  }
  return s.str();
}

std::size_t radar_violations(const nlohmann::json& run) {
  std::size_t n = 0;
  for (const auto& r : run["rules"])
    if (r.value("claims_conservative", false) && r.contains("missed")) n += r["missed"].get<std::size_t>();
  if (run.contains("region")) n += run["region"]["missed"].get<std::size_t>();
  return n;
}

}  // namespace cullcheck
