// cullcheck radar: the radar echo over a terrain (thesis ch. 3.3), generated or read from an
// elevation model; each rule timed and held to the terrain oracle, echo PNGs on request; exit 1
// when a rule misses a witnessed triangle (both rules claim to be conservative).
#include <iostream>
#include <memory>
#include <sstream>

#include "apps/cullcheck/flags.hpp"
#include "apps/cullcheck/subcommands.hpp"
#include "core/errors.hpp"
#include "core/scene_io.hpp"
#include "reports/radar_run.hpp"

namespace cullcheck::cli {
namespace {

// "a,b" or "a,b,c,d" as numbers; InputError naming the flag otherwise.
template <class T>
std::vector<T> numbers(const std::string& text, std::size_t count, const std::string& flag) {
  std::vector<T> out;
  std::stringstream s(text);
  std::string item;
  while (std::getline(s, item, ',')) {
    std::istringstream one(item);
    T v{};
    if (!(one >> v) || !(one >> std::ws).eof()) throw InputError("radar", flag, "'" + text + "' is not " + std::to_string(count) + " comma-separated numbers");
    out.push_back(v);
  }
  if (out.size() != count) throw InputError("radar", flag, "'" + text + "' is not " + std::to_string(count) + " comma-separated numbers");
  return out;
}

}  // namespace

Runner add_radar(CLI::App& app) {
  struct Flags {
    TerrainSource source;
    std::string terrain_params = "{}";
    std::string window, nodata = "fill", at, grid = "100", sector, rule = "both", output;
    RadarRunOptions run;
    double height = 10.0;
    std::size_t step = 1;
    bool no_oracle = false, with_city = false;
    SceneFlags city;
  };
  auto f = std::make_shared<Flags>();
  CLI::App* sub = app.add_subcommand(
      "radar", "Radar echo over terrain (thesis ch. 3.3): the triangles a transmitter sees over 360 degrees or a sector, by the "
               "published rule and a conservative one, held to Embree; echo PNGs; exit 1 when a rule misses a witnessed triangle");
  sub->add_option("--terrain-params", f->terrain_params,
                  "Generated terrain's parameters as JSON (nx, ny, spacing, style fractal|ridged|terraces|flat, relief, base, "
                  "roughness, steps; \"preset\": \"thesis\" for the thesis's 66 x 56 km)")
      ->capture_default_str();
  sub->add_option("--terrain-seed", f->source.seed, "Generated terrain's seed")->capture_default_str();
  sub->add_option("--dem", f->source.dem, "An elevation model GDAL reads (GeoTIFF, ESRI ASCII grid, ...) instead of a generated terrain");
  sub->add_option("--dem-window", f->window, "column,row,columns,rows of the raster to read (0 columns or rows: to its edge)");
  sub->add_option("--dem-step", f->step, "Keep every step-th cell both ways")->check(CLI::Range(1, 1000));
  sub->add_option("--dem-nodata", f->nodata, "NoData cells: fill (from their neighbours) or mask (holes)")
      ->check(CLI::IsMember({"fill", "mask"}))
      ->capture_default_str();
  sub->add_option("--dem-crs", f->source.dem_options.crs, "The raster's CRS when it names none (\"local\": metres as they are)");
  sub->add_option("--at", f->at, "Transmitter's plan position x,y in the terrain's local metres (default: its centre)");
  sub->add_option("--height", f->height, "Transmitter's height above the ground, metres")->capture_default_str();
  sub->add_option("--grid", f->grid, "Cells of the regular grid: G (G x G) or GX,GY")->capture_default_str();
  sub->add_option("--sector", f->sector, "centre,width in degrees of azimuth (from east, counter-clockwise); default: 360");
  sub->add_option("--rule", f->rule,
                  "both (thesis and conservative), all, or a comma-separated list of thesis, conservative, thesis-cell-bound, "
                  "thesis-vertex-test, thesis-beta-min, thesis-immediate-merge (each of the thesis's choices alone)")
      ->capture_default_str();
  sub->add_option("--repeats", f->run.repeats, "Timed echoes per rule (median, p95)")->check(CLI::Range(1, 1000))->capture_default_str();
  sub->add_option("--oracle-subdivisions", f->run.witness.subdivisions, "Oracle samples per triangle: n x n sub-triangle centroids")
      ->check(CLI::Range(1, 16))
      ->capture_default_str();
  sub->add_flag("--no-oracle", f->no_oracle, "Time the rules only");
  sub->add_option("--echo", f->run.echo_prefix, "Write PREFIX_<rule>.png, PREFIX_oracle.png and PREFIX_diff_<rule>.png");
  sub->add_option("--echo-size", f->run.echo_size, "Echo pictures' pixels a side")->check(CLI::Range(16, 8192))->capture_default_str();
  sub->add_option("--range", f->run.range, "Echo pictures' range, metres (default: to the farthest terrain corner)");
  sub->add_option("--region", f->run.region,
                  "A moving mast: also the region echo valid for every position within this many metres of --at (the mast's "
                  "height above what it stands on there), held to the oracle from sample positions in the disc")
      ->check(CLI::NonNegativeNumber);
  sub->add_option("--region-rim", f->run.region_rim, "Region samples: this many on the rim and as many half-way out, and the centre")
      ->check(CLI::Range(1, 256))
      ->capture_default_str();
  sub->add_option("--output,-o", f->output, "Also write the run as JSON to this file");
  sub->add_flag("--with-city", f->with_city,
                "Stand a city's buildings on the terrain (--generator, --seed, --params or --scene, as the other subcommands take "
                "them): walls down to the lowest ground under each, roofs their height above the highest");
  f->city.add(*sub);
  return [f] {
    TerrainSource& source = f->source;
    source.params = parse_json_flag(f->terrain_params, "--terrain-params");
    if (!f->window.empty()) {
      const auto w = numbers<std::size_t>(f->window, 4, "dem-window");
      source.dem_options.column = w[0], source.dem_options.row = w[1], source.dem_options.columns = w[2], source.dem_options.rows = w[3];
    }
    source.dem_options.step = f->step;
    source.dem_options.nodata = f->nodata == "mask" ? formats::NoData::mask : formats::NoData::fill;
    RadarRunOptions o = f->run;
    if (!f->at.empty()) {
      const auto a = numbers<double>(f->at, 2, "at");
      o.at = Vec2{a[0], a[1]};
    }
    o.height = f->height;
    const auto g = f->grid.find(',') == std::string::npos ? std::vector<std::uint32_t>(2, numbers<std::uint32_t>(f->grid, 1, "grid")[0])
                                                          : numbers<std::uint32_t>(f->grid, 2, "grid");
    o.grid_x = g[0], o.grid_y = g[1];
    if (!f->sector.empty()) {
      const auto s = numbers<double>(f->sector, 2, "sector");
      o.sector = {s[0] * kPi / 180.0, s[1] * kPi / 180.0};
    }
    o.rules = parse_radar_rules(f->rule);
    o.oracle = !f->no_oracle;
    if (f->with_city) source.city = f->city.source;
    std::string summary;
    const TerrainScene scene = source.load_scene(&summary);
    const nlohmann::json run = radar_run(scene, summary, source, o);
    std::cout << radar_table(run);
    for (const auto& file : run["echo_files"]) std::cout << "wrote " << file.get<std::string>() << "\n";
    if (!f->output.empty()) write_text_file_atomically(f->output, run.dump(2) + "\n");
    const std::size_t violations = radar_violations(run);
    std::cout << "replay: " << run["replay"].get<std::string>() << "\n";
    return violations == 0 ? 0 : kExitGateFailed;
  };
}

}  // namespace cullcheck::cli
