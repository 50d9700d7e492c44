#include "core/terrain_scene.hpp"

#include <algorithm>
#include <cmath>

#include "core/errors.hpp"

namespace cullcheck {
namespace {

bool inside(const std::vector<Vec2>& poly, Vec2 p) {  // even-odd rule; the boundary may go either way
  bool in = false;
  for (std::size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++) {
    const Vec2 a = poly[i], b = poly[j];
    if ((a.y > p.y) != (b.y > p.y) && p.x < (b.x - a.x) * (p.y - a.y) / (b.y - a.y) + a.x) in = !in;
  }
  return in;
}

bool inside_convex(const std::vector<Vec2>& ring, Vec2 p) {
  for (std::size_t k = 0; k < ring.size(); ++k)
    if (cross(ring[(k + 1) % ring.size()] - ring[k], p - ring[k]) < 0.0) return false;
  return true;
}

}  // namespace

GroundRange ground_under(const Terrain& t, const std::vector<Vec2>& poly) {
  GroundRange g{HUGE_VAL, -HUGE_VAL};
  bool off = false;
  const auto sample = [&](Vec2 p) {
    const double z = t.height_at(p);
    if (!std::isfinite(z)) off = true;
    g.lowest = std::min(g.lowest, z), g.highest = std::max(g.highest, z);
  };
  // In grid units: u across columns, v across rows; triangle edges lie on u, v and u - v integral.
  const auto to_grid = [&](Vec2 p) { return Vec2{(p.x - t.corner.x) / t.dx, (p.y - t.corner.y) / t.dy}; };
  const auto to_plan = [&](Vec2 q) { return Vec2{t.corner.x + q.x * t.dx, t.corner.y + q.y * t.dy}; };
  for (std::size_t k = 0; k < poly.size(); ++k) {
    const Vec2 a = to_grid(poly[k]), b = to_grid(poly[(k + 1) % poly.size()]);
    sample(poly[k]);
    // Crossings with the lines f(q) = n for integral n, f one of u, v, u - v.
    const auto crossings = [&](double fa, double fb) {
      if (fa == fb) return;
      for (double n = std::ceil(std::min(fa, fb)); n <= std::floor(std::max(fa, fb)); n += 1.0) {
        const double s = (n - fa) / (fb - fa);
        sample(to_plan(a + (b - a) * s));
      }
    };
    crossings(a.x, b.x);
    crossings(a.y, b.y);
    crossings(a.x - a.y, b.x - b.y);
  }
  Box2 box;
  for (const Vec2& p : poly) box.extend(p);
  const Vec2 lo = to_grid(box.lo), hi = to_grid(box.hi);
  for (double j = std::max(0.0, std::ceil(lo.y)); j <= std::min(double(t.ny - 1), std::floor(hi.y)); j += 1.0)
    for (double i = std::max(0.0, std::ceil(lo.x)); i <= std::min(double(t.nx - 1), std::floor(hi.x)); i += 1.0) {
      const Vec2 p = to_plan({i, j});
      if (inside(poly, p)) sample(p);
    }
  if (off) return {NAN, NAN};
  return g;
}

std::size_t building_triangle_count(const StandingBuilding& b) {
  std::size_t n = 0;
  for (const StandingPrism& p : b.prisms) n += prism_triangle_count(p);
  return n;
}

TerrainScene stand_on_terrain(Terrain terrain, const Scene& city, std::string city_source) {
  if (!city.meshes.empty())
    throw InputError("city", "meshes", std::to_string(city.meshes.size()) + " mesh objects: only prism buildings stand on terrain");
  TerrainScene out;
  out.terrain = std::move(terrain);
  out.city = std::move(city_source);
  for (const Building& b : city.buildings) {
    const GroundRange g = ground_under(out.terrain, b.footprint);
    if (!std::isfinite(g.lowest))
      throw InputError("building " + std::to_string(b.id), "footprint", "stands partly off the terrain or over a NoData hole");
    StandingBuilding s;
    s.id = b.id;
    for (const ConvexVerticalPrism& p : b.prisms) s.prisms.push_back({p.ring, g.lowest, g.highest + p.height});
    out.buildings.push_back(std::move(s));
  }
  return out;
}

double standing_height(const TerrainScene& scene, Vec2 p) {
  double z = scene.terrain.height_at(p);
  if (!std::isfinite(z)) return z;
  for (const StandingBuilding& b : scene.buildings)
    for (const StandingPrism& prism : b.prisms)
      if (inside_convex(prism.ring, p)) z = std::max(z, prism.roof);
  return z;
}

std::int64_t roof_triangle_at(const TerrainScene& scene, Vec2 p, double* roof) {
  std::int64_t best = -1;
  double top = -HUGE_VAL;
  std::size_t first = 0;  // the prism's first triangle
  for (const StandingBuilding& b : scene.buildings)
    for (const StandingPrism& prism : b.prisms) {
      const std::size_t n = prism.ring.size();
      if (prism.roof > top && inside_convex(prism.ring, p))
        for (std::size_t k = 1; k + 1 < n; ++k) {  // the fan triangle (0, k, k + 1) holding p
          const Vec2 a = prism.ring[0], b2 = prism.ring[k], c = prism.ring[k + 1];
          if (cross(b2 - a, p - a) >= 0.0 && cross(c - b2, p - b2) >= 0.0 && cross(a - c, p - c) >= 0.0) {
            best = std::int64_t(first + 2 * n + (k - 1));
            top = prism.roof;
            break;
          }
        }
      first += prism_triangle_count(prism);
    }
  if (roof) *roof = top;
  return best;
}

std::int64_t building_at(const TerrainScene& scene, Vec2 p) {
  for (std::size_t k = 0; k < scene.buildings.size(); ++k)
    for (const StandingPrism& prism : scene.buildings[k].prisms)
      if (inside_convex(prism.ring, p)) return std::int64_t(k);
  return -1;
}

}  // namespace cullcheck
