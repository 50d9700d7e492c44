// The radar's region echo (engine/radar/region_echo.hpp: one echo for every mast position in a
// disc, the moving platform's reuse) held to the terrain oracle from sample positions in the
// disc (its centre, its rim, half-way out) over generated terrains with and without holes and
// small cities on them, radii from 1 m to 1 km, masts 2 to 500 m, grids and sectors. The
// property counts that the region was needed (the centre's own echo misses what a sample
// sees) and that it still culls; straw men show the check can fail.
#include <gtest/gtest.h>
#include <rapidcheck.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "core/sorted_sets.hpp"
#include "core/terrain_scene.hpp"
#include "engine/radar/radar_echo.hpp"
#include "engine/radar/region_echo.hpp"
#include "engine/radar/triangle_grid.hpp"
#include "generators/terrain_gen.hpp"
#include "oracle/terrain_oracle.hpp"
#include "property_run.hpp"
#include "terrain_cases.hpp"
#include "reports/radar_platform.hpp"
#include "reports/radar_region.hpp"
#include "reports/radar_run.hpp"
#include "reports/scene_source.hpp"

namespace cullcheck {
namespace {

using radar::Sector;
using radar::TriangleGrid;

struct RegionCase {
  generators::TerrainParams params;
  std::uint64_t seed = 1;
  std::optional<SceneSource> city;
  Vec2 centre;
  double radius = 10.0, height = 10.0;
  std::uint32_t gx = 8, gy = 8;
  Sector sector;
};

std::string replay(const RegionCase& c) {
  TerrainSource source;
  source.params = generators::terrain_params_to_json(c.params);
  source.seed = c.seed;
  source.city = c.city;
  RadarRunOptions o;
  o.height = c.height;
  o.grid_x = c.gx, o.grid_y = c.gy;
  o.sector = c.sector;
  o.rules = {"conservative"};
  o.region = c.radius;
  o.region_rim = 4;
  return radar_replay_command(source, o, c.centre);
}

rc::Gen<RegionCase> region_cases() {
  return rc::gen::exec([] {
    RegionCase c;
    TerrainCase t = draw_terrain_case(4);
    c.params = t.params, c.seed = t.seed, c.city = t.city;
    const double w = (c.params.nx - 1) * c.params.spacing, h = (c.params.ny - 1) * c.params.spacing;
    c.centre = Vec2{-0.5 * w, -0.5 * h} + Vec2{*rc::gen::inRange(0, 1001) / 1000.0 * w, *rc::gen::inRange(0, 1001) / 1000.0 * h};
    // From a sliver of a cell to beyond the terrain.
    c.radius = *rc::gen::element(0.01, 0.1, 0.3, 1.0, 3.0) * c.params.spacing * (*rc::gen::inRange(1, 11) / 2.0);
    c.height = *rc::gen::element(2.0, 2.0, 10.0, 30.0, 100.0, 500.0) + *rc::gen::inRange(0, 100) / 10.0;
    c.gx = std::uint32_t(*rc::gen::inRange(1, 25));
    c.gy = *rc::gen::inRange(0, 3) == 0 ? c.gx : std::uint32_t(*rc::gen::inRange(1, 25));
    if (*rc::gen::inRange(0, 4) == 0) c.sector = {*rc::gen::inRange(0, 360) * kPi / 180.0, *rc::gen::inRange(5, 200) * kPi / 180.0};
    return c;
  });
}

struct RegionCounts {
  int cases = 0, needed = 0, culled = 0, holes = 0, cities = 0, sectors = 0, wide = 0;
  std::size_t pvs = 0, witnessed = 0;
};

// A PVS for the case (the region echo, or a straw man) checked from the samples of the disc.
using RegionMethod = std::function<std::vector<std::uint32_t>(const TerrainScene&, const TriangleGrid&, const RegionCase&)>;

void check_region_case(RegionCounts& n, const RegionMethod& method) {
  const RegionCase c = *region_cases();
  const TerrainScene scene = stand_on_terrain(generators::generate_terrain(c.params, c.seed), c.city ? c.city->load() : Scene{});
  RC_PRE(std::isfinite(standing_height(scene, c.centre)));
  const TriangleGrid grid(radar::RadarSurface(scene), c.gx, c.gy);
  const oracle::TerrainOracle truth(scene);
  oracle::TerrainWitnessOptions w;
  w.threads = 1;
  w.sector_centre = c.sector.centre, w.sector_width = c.sector.width;
  const std::vector<std::uint32_t> pvs = method(scene, grid, c);
  const radar::Echo centre_echo =
      radar::RadarEcho(grid, radar::RadarRule::conservative).compute(region_sample_eyes(scene, c.centre, c.radius, c.height, 4).front(), c.sector);
  std::vector<std::uint32_t> all;
  bool needed = false;
  for (const Vec3& eye : region_sample_eyes(scene, c.centre, c.radius, c.height, 4)) {
    const auto seen = truth.witnessed(eye, w);
    const auto miss = missing(seen.witnessed, pvs);
    if (!miss.empty())
      RC_LOG() << miss.size() << " triangles witnessed from (" << eye.x << ", " << eye.y << ", " << eye.z << ") missed, first " << miss[0]
               << "\nreplay: " << replay(c) << "\n";
    RC_ASSERT(miss.empty());
    needed = needed || !missing(seen.witnessed, centre_echo.visible).empty();
    all = united(all, seen.witnessed);
  }
  ++n.cases;
  n.needed += needed;
  n.culled += pvs.size() < radar::RadarSurface(scene).present_triangle_count();
  n.holes += c.params.holes > 0.0;
  n.cities += c.city.has_value();
  n.sectors += c.sector.width < kTwoPi;
  n.wide += c.radius > 2.0 * c.params.spacing;
  n.pvs += pvs.size();
  n.witnessed += all.size();
}

std::vector<std::uint32_t> region_echo(const TerrainScene& scene, const TriangleGrid& grid, const RegionCase& c) {
  return radar::RegionEcho(grid).compute(mast_region(scene, c.centre, c.radius, c.height), c.sector).visible;
}

TEST(RegionEcho, HoldsEveryTriangleWitnessedFromAnywhereInItsDisc) {
  RegionCounts n;
  const auto outcome = run_property("radar-region-holds-witnessed", 400, true, [&n] { check_region_case(n, region_echo); });
  std::printf("%d cases: the centre's own echo missed a sample's witness in %d, the region culled in %d; holes %d, cities %d, sectors %d, "
              "radius over two cells %d; PVS %zu over the samples' witnessed union %zu\n",
              n.cases, n.needed, n.culled, n.holes, n.cities, n.sectors, n.wide, n.pvs, n.witnessed);
  ASSERT_TRUE(outcome.held);
  if (reproducing()) return;
  // The hard cases were reached: the region mattered (a point echo would have failed), and the
  // region echo is no "return everything".
  EXPECT_GE(n.needed, n.cases / 4);
  EXPECT_GE(n.culled, n.cases / 3);
  EXPECT_GE(n.holes, 10);
  EXPECT_GE(n.cities, 20);
  EXPECT_GE(n.sectors, 20);
  EXPECT_GE(n.wide, 30);
}

// Straw men the same check catches: the centre's own echo used for the whole disc, and a region
// echo shrunk for a quarter of the disc's radius.
TEST(RegionEcho, StrawMenFailTheProperty) {
  RegionCounts n;
  const auto centre = run_property(
      "radar-region-straw-centre", 200, false,
      [&n] {
        check_region_case(n, [](const TerrainScene& scene, const TriangleGrid& grid, const RegionCase& c) {
          return radar::RadarEcho(grid, radar::RadarRule::conservative).compute(region_sample_eyes(scene, c.centre, c.radius, c.height, 1).front(), c.sector).visible;
        });
      },
      true);
  EXPECT_FALSE(centre.held);
  const auto quarter = run_property(
      "radar-region-straw-quarter", 200, false,
      [&n] {
        check_region_case(n, [](const TerrainScene& scene, const TriangleGrid& grid, const RegionCase& c) {
          radar::MastRegion r = mast_region(scene, c.centre, c.radius, c.height);
          r.radius *= 0.25;
          return radar::RegionEcho(grid).compute(r, c.sector).visible;
        });
      },
      true);
  EXPECT_FALSE(quarter.held);
}

// With no radius the region echo is the conservative point echo, triangle for triangle; a disc
// costs triangles, more the wider (pinned on a ridged terrain, 30 m mast).
TEST(RegionEcho, WithNoRadiusItIsThePointEchoAndWiderDiscsSendMore) {
  generators::TerrainParams p;
  p.nx = p.ny = 129, p.spacing = 30, p.style = "ridged", p.relief = 400;
  const TerrainScene scene = stand_on_terrain(generators::generate_terrain(p, 4), Scene{});
  const Vec2 at{300, -200};
  const TriangleGrid grid(radar::RadarSurface(scene), 32, 32);
  const radar::Echo point = radar::RadarEcho(grid, radar::RadarRule::conservative).compute({at.x, at.y, scene.terrain.height_at(at) + 30});
  radar::RegionEcho region(grid);
  EXPECT_EQ(region.compute(mast_region(scene, at, 0.0, 30.0)).visible, point.visible);
  EXPECT_EQ(point.visible.size(), 6563u);
  std::vector<std::size_t> sizes;
  for (double r : {25.0, 100.0, 300.0}) sizes.push_back(region.compute(mast_region(scene, at, r, 30.0)).visible.size());
  EXPECT_EQ(sizes, (std::vector<std::size_t>{9223, 12000, 17735}));
}

// The eroded floors bound the ground: every point of the terrain within the radius of a
// triangle lies above the triangle's floor, and above each point of the triangle less its drop.
TEST(RegionEcho, ErodedFloorsLieUnderTheGroundWithinTheRadius) {
  generators::TerrainParams p;
  p.nx = 33, p.ny = 21, p.spacing = 10, p.style = "ridged", p.relief = 200;
  const Terrain t = generators::generate_terrain(p, 11);
  const radar::RadarSurface surface(t);
  std::uint64_t state = 12345;
  const auto uniform = [&state] {
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    return double(state >> 11) / double(1ULL << 53);
  };
  std::size_t checked = 0, floor_binds = 0;
  for (const double radius : {0.0, 4.0, 15.0, 60.0}) {
    const radar::ShrunkFloors f = radar::eroded_floors(surface, radius);
    ASSERT_EQ(f.floors.size(), t.triangle_count());
    for (std::size_t tri = 0; tri < t.triangle_count(); tri += 7) {
      const auto v = t.triangle(tri);
      for (int k = 0; k < 20; ++k) {
        double a = uniform(), b = uniform();
        if (a + b > 1) a = 1 - a, b = 1 - b;
        const Vec3 x = v[0] + (v[1] - v[0]) * a + (v[2] - v[0]) * b;
        const double turn = kTwoPi * uniform(), out = radius * std::sqrt(uniform());
        const Vec2 y = plan(x) + Vec2{std::cos(turn), std::sin(turn)} * out;
        const double hy = t.height_at(y);
        if (!std::isfinite(hy)) continue;  // off the terrain
        ++checked;
        EXPECT_GE(hy, f.floors[tri] - 1e-9) << "triangle " << tri << " radius " << radius;
        EXPECT_GE(hy, x.z - f.drops[tri] - 1e-9) << "triangle " << tri << " radius " << radius;
        floor_binds += f.floors[tri] > x.z - f.drops[tri];
      }
    }
    if (radius == 0.0) {  // no erosion: a triangle's floor is the lowest of its cell's corners, no drop
      for (std::size_t tri = 0; tri < t.triangle_count(); ++tri) ASSERT_EQ(f.drops[tri], 0.0);
    }
  }
  EXPECT_GT(checked, 3000u);
  EXPECT_GT(floor_binds, 100u);  // both bounds do work
}

// The moving platform reuses each region echo over the rotations inside its disc (placed ahead
// of the vehicle): 12 rotations 10 m apart make 3 discs of radius 15 m and 2 of 40 m; every
// rotation's witnessed triangles are in the echo it uses.
TEST(RegionEcho, TheMovingPlatformReusesEachRegionWhileInsideAndMissesNothing) {
  generators::TerrainParams p;
  p.nx = p.ny = 41, p.spacing = 20, p.style = "fractal", p.relief = 150;
  const Terrain t = generators::generate_terrain(p, 3);
  PlatformOptions o;
  o.positions = 12, o.step = 10, o.height = 5, o.grid = 10, o.radii = {15, 40}, o.oracle_every = 1;
  const nlohmann::json m = radar_moving_platform(t, o);
  EXPECT_EQ(m["oracle_rotations"], 12);
  EXPECT_EQ(m["missed"], 0);
  ASSERT_EQ(m["regions"].size(), 2u);
  EXPECT_EQ(m["regions"][0]["regions"], 3);
  EXPECT_EQ(m["regions"][1]["regions"], 2);
  for (const auto& r : m["regions"]) {
    EXPECT_EQ(r["missed"], 0) << r.dump();
    EXPECT_GE(r["pvs_over_point_median"].get<double>(), 1.0);
  }
  EXPECT_NE(radar_moving_platform_text(m).find("region reused"), std::string::npos);
}

}  // namespace
}  // namespace cullcheck
