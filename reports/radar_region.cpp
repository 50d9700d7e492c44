#include "reports/radar_region.hpp"

#include <algorithm>
#include <cmath>

#include "core/errors.hpp"
#include "core/replay_text.hpp"
#include "core/sorted_sets.hpp"

namespace cullcheck {

radar::MastRegion mast_region(const TerrainScene& scene, Vec2 centre, double radius, double height) {
  const Terrain& t = scene.terrain;
  if (!std::isfinite(t.height_at(centre)))
    throw InputError("transmitter", "at", "(" + round_trip_text(centre.x) + ", " + round_trip_text(centre.y) + ") is off the terrain or over a NoData hole");
  if (!(radius >= 0.0) || !std::isfinite(radius)) throw InputError("radar", "region", "its radius must be finite, 0 or more");
  const Box2 plan = t.bounds().plan();
  const Box2 square{{std::max(plan.lo.x, centre.x - radius), std::max(plan.lo.y, centre.y - radius)},
                    {std::min(plan.hi.x, centre.x + radius), std::min(plan.hi.y, centre.y + radius)}};
  GroundRange g = ground_under(t, {square.lo, {square.hi.x, square.lo.y}, square.hi, {square.lo.x, square.hi.y}});
  if (!std::isfinite(g.lowest) || !std::isfinite(g.highest)) {
    // Holes under the square: the present vertices bound the ground that is there.
    g = {HUGE_VAL, -HUGE_VAL};
    for (std::size_t v = 0; v < t.vertex_count(); ++v) {
      const Vec2 p = t.corner + Vec2{double(v % t.nx) * t.dx, double(v / t.nx) * t.dy};
      if (t.is_hole(v) || std::abs(p.x - centre.x) > radius + t.dx || std::abs(p.y - centre.y) > radius + t.dy) continue;
      g.lowest = std::min(g.lowest, t.z[v]), g.highest = std::max(g.highest, t.z[v]);
    }
  }
  double top = g.highest;
  for (const StandingBuilding& b : scene.buildings)
    for (const StandingPrism& p : b.prisms) {
      Box2 box;
      for (const Vec2& v : p.ring) box.extend(v);
      if (box.lo.x <= square.hi.x && box.hi.x >= square.lo.x && box.lo.y <= square.hi.y && box.hi.y >= square.lo.y) top = std::max(top, p.roof);
    }
  return {centre, radius, g.lowest + height, top + height};
}

std::vector<Vec3> region_sample_eyes(const TerrainScene& scene, Vec2 centre, double radius, double height, int rim) {
  std::vector<Vec2> at{centre};
  for (int k = 0; k < rim; ++k) {
    const double a = kTwoPi * k / rim, b = kTwoPi * (k + 0.5) / rim;
    at.push_back(centre + Vec2{std::cos(a), std::sin(a)} * radius);
    at.push_back(centre + Vec2{std::cos(b), std::sin(b)} * (0.5 * radius));
  }
  std::vector<Vec3> out;
  for (const Vec2& p : at) {
    const double z = standing_height(scene, p);
    if (std::isfinite(z)) out.push_back({p.x, p.y, z + height});
  }
  return out;
}

RegionCheck check_region_echo(const TerrainScene& scene, const radar::TriangleGrid& grid, const oracle::TerrainOracle& truth,
                              Vec2 centre, double radius, double height, int rim, const radar::Sector& sector,
                              oracle::TerrainWitnessOptions witness) {
  RegionCheck out;
  out.echo = radar::RegionEcho(grid).compute(mast_region(scene, centre, radius, height), sector);
  const std::vector<Vec3> eyes = region_sample_eyes(scene, centre, radius, height, rim);
  const radar::Echo point = radar::RadarEcho(grid, radar::RadarRule::conservative).compute(eyes.front(), sector);
  witness.sector_centre = sector.centre, witness.sector_width = sector.width;
  std::vector<std::uint32_t> all;
  for (const Vec3& eye : eyes) {
    const oracle::TerrainWitness seen = truth.witnessed(eye, witness);
    const auto miss = missing(seen.witnessed, out.echo.visible);
    out.missed += miss.size();
    if (!miss.empty()) out.first_missed.push_back(miss.front());
    out.centre_echo_missed += missing(seen.witnessed, point.visible).size();
    all = united(all, seen.witnessed);
  }
  out.samples = eyes.size();
  out.witnessed_union = all.size();
  return out;
}

}  // namespace cullcheck
