#include "reports/radar_platform.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "core/elapsed.hpp"
#include "core/errors.hpp"
#include "core/sorted_sets.hpp"
#include "core/terrain_scene.hpp"
#include "engine/radar/radar_echo.hpp"
#include "engine/radar/region_echo.hpp"
#include "engine/radar/triangle_grid.hpp"
#include "oracle/terrain_oracle.hpp"
#include "reports/radar_region.hpp"
#include "reports/statistics.hpp"

namespace cullcheck {
namespace {

using nlohmann::json;

}  // namespace

json radar_moving_platform(const Terrain& terrain, const PlatformOptions& o) {
  if (o.positions < 1) throw InputError("radar", "platform", "needs at least one position");
  for (double r : o.radii)
    if (!(r > 0.0) || !std::isfinite(r)) throw InputError("radar", "platform", "a region radius must be a positive number of metres");
  const TerrainScene scene = stand_on_terrain(terrain, Scene{});
  const auto t0 = std::chrono::steady_clock::now();
  const radar::RadarSurface surface(scene);
  const radar::TriangleGrid grid(surface, o.grid, o.grid);
  const double grid_ms = ms_since(t0);
  const Vec2 direction{1.0, 0.0};
  const Vec2 start = terrain.bounds().plan().center() - direction * (0.5 * o.step * (o.positions - 1));
  std::vector<Vec3> eyes;
  for (int k = 0; k < o.positions; ++k) {
    const Vec2 at = start + direction * (o.step * k);
    const double ground = terrain.height_at(at);
    if (!std::isfinite(ground)) throw InputError("radar", "platform", "the drive leaves the terrain or crosses a hole");
    eyes.push_back({at.x, at.y, ground + o.height});
  }

  // Every rotation from scratch, and the share of each PVS the one before held.
  radar::RadarEcho echo(grid, radar::RadarRule::conservative);
  std::vector<double> ms, kept;
  std::vector<std::vector<std::uint32_t>> pvs;
  for (const Vec3& eye : eyes) {
    const auto t1 = std::chrono::steady_clock::now();
    radar::Echo e = echo.compute(eye);
    ms.push_back(ms_since(t1));
    if (!pvs.empty()) kept.push_back(e.visible.empty() ? 1.0 : double(common_count(e.visible, pvs.back())) / double(e.visible.size()));
    pvs.push_back(std::move(e.visible));
  }
  double total = 0.0;
  for (double m : ms) total += m;

  // The oracle at every oracle_every-th rotation.
  std::vector<std::size_t> checked;
  std::vector<std::vector<std::uint32_t>> witnessed;
  std::size_t point_missed = 0;
  if (o.oracle_every > 0) {
    const oracle::TerrainOracle truth(scene);
    oracle::TerrainWitnessOptions w;
    w.subdivisions = o.oracle_subdivisions;
    for (std::size_t k = 0; k < eyes.size(); k += std::size_t(o.oracle_every)) {
      checked.push_back(k);
      witnessed.push_back(truth.witnessed(eyes[k], w).witnessed);
      point_missed += missing(witnessed.back(), pvs[k]).size();
    }
  }

  json out = {{"rule", "conservative"},
              {"grid", o.grid},
              {"grid_build_ms", grid_ms},
              {"positions", o.positions},
              {"step_m", o.step},
              {"height_m", o.height},
              {"ms_median", median(ms)},
              {"ms_p95", percentile(ms, 95)},
              {"ms_total", total},
              {"pvs_median", 0},
              {"previous_pvs_share_median", kept.empty() ? 0.0 : median(kept)},
              {"previous_pvs_share_min", kept.empty() ? 0.0 : *std::min_element(kept.begin(), kept.end())},
              {"oracle_rotations", checked.size()},
              {"missed", point_missed}};
  std::vector<double> sizes;
  for (const auto& p : pvs) sizes.push_back(double(p.size()));
  out["pvs_median"] = median(sizes);

  // Region echoes reused while the vehicle stays inside.
  out["regions"] = json::array();
  for (const double radius : o.radii) {
    radar::RegionEcho region(grid);
    std::vector<double> region_ms, over_point;
    std::vector<std::uint32_t> current;
    std::optional<Vec2> centre;
    std::size_t regions = 0, missed = 0, next_check = 0;
    double region_total = 0.0;
    for (std::size_t k = 0; k < eyes.size(); ++k) {
      const Vec2 at = plan(eyes[k]);
      if (!centre || length(at - *centre) > radius) {
        // The next disc starts at the vehicle and lies ahead of it, clamped onto the terrain.
        Vec2 c = at + direction * radius;
        if (!terrain.bounds().plan().contains(c)) c = at;
        const radar::MastRegion r = mast_region(scene, c, radius, o.height);
        const auto t1 = std::chrono::steady_clock::now();
        current = region.compute(r).visible;
        region_ms.push_back(ms_since(t1));
        region_total += region_ms.back();
        centre = c;
        ++regions;
      }
      over_point.push_back(pvs[k].empty() ? 1.0 : double(current.size()) / double(pvs[k].size()));
      if (next_check < checked.size() && checked[next_check] == k) missed += missing(witnessed[next_check++], current).size();
    }
    out["regions"].push_back({{"radius_m", radius},
                              {"regions", regions},
                              {"rotations_per_region", double(eyes.size()) / double(regions)},
                              {"region_ms_median", median(region_ms)},
                              {"region_ms_max", *std::max_element(region_ms.begin(), region_ms.end())},
                              {"ms_total", region_total},
                              {"speedup", region_total > 0.0 ? total / region_total : 0.0},
                              {"pvs_over_point_median", median(over_point)},
                              {"pvs_over_point_max", *std::max_element(over_point.begin(), over_point.end())},
                              {"oracle_rotations", checked.size()},
                              {"missed", missed}});
  }
  return out;
}

std::string radar_moving_platform_text(const json& m) {
  std::ostringstream s;
  char line[400];
  std::snprintf(line, sizeof line,
                "  moving platform: %d rotations %.0f m apart (mast %.0f m), grid %u (built once in %.0f ms): each rotation from scratch "
                "%.1f ms median, %.1f p95, %.0f ms in all, %.0f triangles median; the previous rotation's PVS held %.1f%% of each "
                "(median; lowest %.1f%%); oracle at %zu rotations: %zu missed\n",
                m["positions"].get<int>(), m["step_m"].get<double>(), m["height_m"].get<double>(), m["grid"].get<std::uint32_t>(),
                m["grid_build_ms"].get<double>(), m["ms_median"].get<double>(), m["ms_p95"].get<double>(), m["ms_total"].get<double>(),
                m["pvs_median"].get<double>(), 100 * m["previous_pvs_share_median"].get<double>(),
                100 * m["previous_pvs_share_min"].get<double>(), m["oracle_rotations"].get<std::size_t>(), m["missed"].get<std::size_t>());
  s << line;
  s << "    region reused   regions  rotations/region  region ms (median, max)  ms in all  speedup  PVS / rotation's (median, max)  missed\n";
  for (const json& r : m["regions"]) {
    std::snprintf(line, sizeof line, "    %8.0f m %12zu %17.1f %12.1f %10.1f %10.0f %8.2f %14.2f %8.2f %14zu\n", r["radius_m"].get<double>(),
                  r["regions"].get<std::size_t>(), r["rotations_per_region"].get<double>(), r["region_ms_median"].get<double>(),
                  r["region_ms_max"].get<double>(), r["ms_total"].get<double>(), r["speedup"].get<double>(),
                  r["pvs_over_point_median"].get<double>(), r["pvs_over_point_max"].get<double>(), r["missed"].get<std::size_t>());
    s << line;
  }
  return s.str();
}

}  // namespace cullcheck
