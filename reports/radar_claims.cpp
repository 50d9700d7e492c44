#include "reports/radar_claims.hpp"

#include <algorithm>
#include <chrono>

#include "core/elapsed.hpp"
#include "core/sorted_sets.hpp"
#include "engine/radar/radar_echo.hpp"
#include "engine/radar/triangle_grid.hpp"
#include "generators/random.hpp"
#include "generators/terrain_gen.hpp"
#include "oracle/terrain_oracle.hpp"
#include "reports/radar_run.hpp"

namespace cullcheck {
namespace {

struct RuleClaim {
  const char* rule;  // radar::named_rules() name
  const char* id;
  const char* statement;
};

const RuleClaim kRuleClaims[] = {
    {"thesis", "thesis-3.3-radar-echo",
     "the object-space horizon over a grid of terrain triangles, as published (step 1: the transmitter cell's facing "
     "triangles; step 2: cells front to back, C2 at a cell's nearest point and highest value, a triangle visible when a "
     "vertex clears the horizon, its shadow at β_min, raised at once) finds every visible triangle"},
    {"thesis-cell-bound", "thesis-3.3-c2-cell-bound",
     "a cell can be culled when its highest value placed at its nearest point (C2) lies under the horizon (the other "
     "choices conservative)"},
    {"thesis-vertex-test", "thesis-3.3-vertex-test",
     "a triangle is visible exactly when one of its vertices clears the horizon over its span (the other choices "
     "conservative)"},
    {"thesis-beta-min", "thesis-3.3-beta-min-shadow",
     "a visible triangle's shadow may raise the horizon to β_min, the lower elevation of its two extreme-azimuth "
     "vertices (Fig. 3.12-3.13; examined for prisms in ch. 3.1.2, here for triangles; the other choices conservative)"},
    {"thesis-immediate-merge", "thesis-3.3-immediate-merge",
     "a visible triangle's shadow may raise the horizon at once, before the cells still to come are nearer than its far "
     "end (the other choices conservative)"},
    {"conservative", "cullcheck-radar-conservative",
     "cells and triangles bounded over their whole distance range, shadows from the far chain's lower bound merged once "
     "the sweep has passed the triangle, no shadows through NoData holes: every witnessed triangle is in the PVS"},
};

}  // namespace

std::vector<ClaimCheck> check_radar_claims(const ClaimSearchOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  std::vector<ClaimCheck> claims;
  for (const RuleClaim& r : kRuleClaims) {
    ClaimCheck c;
    c.id = r.id;
    c.source = std::string(r.rule) == "conservative" ? "cullcheck (engine/radar/radar_echo.hpp)" : "Koldas thesis, ch. 3.3.2";
    c.statement = r.statement;
    c.method = std::string("radar --rule ") + r.rule;
    claims.push_back(std::move(c));
  }
  std::vector<ClaimCheck*> pointers;
  for (ClaimCheck& c : claims) pointers.push_back(&c);
  search_scenes(options.scenes, options.threads, options.shard, pointers, "claims search: radar echo over terrain",
                [&options](int index, std::vector<ClaimCheck>& partial) {
    generators::Random r = generators::Random::stream(options.seed, 0x7ADA7, static_cast<std::uint64_t>(index));
    const char* styles[] = {"fractal", "ridged", "terraces", "flat"};
    generators::TerrainParams p;
    p.style = styles[r.uniform_int(0, 3)];
    p.nx = int(r.uniform_int(5, 33));
    p.ny = int(r.uniform_int(5, 33));
    p.spacing = double(r.uniform_int(1, 12)) * 5.0;
    p.relief = p.style == "flat" ? 0.0 : double(r.uniform_int(20, 400));
    p.steps = int(r.uniform_int(2, 8));
    p.holes = r.bernoulli(0.2) ? 0.1 : 0.0;
    TerrainSource source;
    source.params = generators::terrain_params_to_json(p);
    source.seed = options.seed * 1000 + std::uint64_t(index);
    // A small city standing on a quarter of the terrains that can hold one.
    if (r.bernoulli(0.25) && p.holes == 0.0 && (p.nx - 1) * p.spacing >= 130 && (p.ny - 1) * p.spacing >= 130) {
      SceneSource city;
      city.generator = "manhattan";
      city.seed = source.seed;
      city.parameters_json = nlohmann::json{{"blocks_x", r.uniform_int(1, 2)}, {"blocks_y", r.uniform_int(1, 2)},
                                            {"block_size", 40.0}, {"street_width", 10.0}}
                                 .dump();
      source.city = city;
    }
    const TerrainScene scene = source.load_scene();
    const Terrain& terrain = scene.terrain;
    const radar::RadarSurface surface(scene);
    const oracle::TerrainOracle truth(scene);
    std::vector<std::pair<std::uint32_t, std::uint32_t>> grids;
    for (int g = 0; g < 3; ++g) grids.push_back({std::uint32_t(r.uniform_int(1, 24)), std::uint32_t(r.uniform_int(1, 24))});
    std::vector<radar::TriangleGrid> built;
    for (const auto& [gx, gy] : grids) built.emplace_back(surface, gx, gy);
    std::size_t highest = 0;
    for (std::size_t v = 0; v < terrain.vertex_count(); ++v)
      if (!terrain.is_hole(v) && (terrain.is_hole(highest) || terrain.z[v] > terrain.z[highest])) highest = v;
    const double heights[] = {2, 10, 30, 100, 500};
    for (int k = 0; k < options.cameras_per_scene; ++k) {
      const Box2 plan = terrain.bounds().plan();
      Vec2 at{r.uniform_real(plan.lo.x, plan.hi.x), r.uniform_real(plan.lo.y, plan.hi.y)};
      const int place = int(r.uniform_int(0, 3));  // 0, 1 anywhere; 2 on a vertex; 3 on the crest
      if (place == 2)
        at = terrain.corner + Vec2{double(r.uniform_int(0, terrain.nx - 1)) * terrain.dx, double(r.uniform_int(0, terrain.ny - 1)) * terrain.dy};
      if (place == 3) at = terrain.corner + Vec2{double(highest % terrain.nx) * terrain.dx, double(highest / terrain.nx) * terrain.dy};
      RadarRunOptions o;
      o.height = heights[r.uniform_int(0, 4)];
      const std::size_t g = std::size_t(r.uniform_int(0, 2));
      o.grid_x = grids[g].first, o.grid_y = grids[g].second;
      if (r.bernoulli(0.3)) o.sector = {r.uniform_real(0.0, kTwoPi), r.uniform_real(0.1, kPi)};
      const double ground = standing_height(scene, at);  // on a roof when on a building
      if (!std::isfinite(ground)) continue;  // over a hole
      const Vec3 eye{at.x, at.y, ground + o.height};
      oracle::TerrainWitnessOptions w;
      w.sector_centre = o.sector.centre, w.sector_width = o.sector.width;
      w.threads = 1;
      const oracle::TerrainWitness seen = truth.witnessed(eye, w);
      for (std::size_t i = 0; i < partial.size(); ++i) {
        ClaimCheck& claim = partial[i];
        const radar::Echo echo = radar::RadarEcho(built[g], *radar::rules_named(kRuleClaims[i].rule)).compute(eye, o.sector);
        ++claim.frames_checked;
        const auto missed = missing(seen.witnessed, echo.visible);
        claim.violations += missed.size();
        if (missed.empty() || !claim.holds) continue;
        claim.holds = false;
        o.rules = {kRuleClaims[i].rule};
        claim.counterexample_replay = radar_replay_command(source, o, at);
        const auto w_at = std::lower_bound(seen.witnessed.begin(), seen.witnessed.end(), missed[0]) - seen.witnessed.begin();
        const Vec3 q = seen.witness_points[std::size_t(w_at)];
        claim.counterexample_detail = std::to_string(missed.size()) + " of " + std::to_string(seen.witnessed.size()) +
                                      " witnessed triangles missed; triangle " + std::to_string(missed[0]) +
                                      " is hit first by the ray from the transmitter to (" + std::to_string(q.x) + ", " +
                                      std::to_string(q.y) + ", " + std::to_string(q.z) + ")";
      }
    }
  });
  const double seconds = seconds_since(start);
  for (ClaimCheck& c : claims) c.search_seconds = seconds;
  return claims;
}

}  // namespace cullcheck
