#include "generators/open_space.hpp"

#include <algorithm>
#include <cmath>

namespace cullcheck::generators {
namespace {

Box2 plan_box(const Building& b) { return b.bounds.plan(); }

}  // namespace

bool point_in_footprint(const std::vector<Vec2>& ring, Vec2 p) {
  // Crossing number with the half-open rule, plus an explicit boundary test so that points on
  // a wall or a corner are inside whatever the rounding of the crossing test.
  bool inside = false;
  for (std::size_t i = 0, n = ring.size(), j = n - 1; i < n; j = i++) {
    const Vec2 a = ring[j], b = ring[i];
    if (cross(b - a, p - a) == 0.0 && std::min(a.x, b.x) <= p.x && p.x <= std::max(a.x, b.x) &&
        std::min(a.y, b.y) <= p.y && p.y <= std::max(a.y, b.y))
      return true;
    if ((a.y > p.y) != (b.y > p.y)) {
      const double x = a.x + (p.y - a.y) * (b.x - a.x) / (b.y - a.y);
      if (p.x < x) inside = !inside;
    }
  }
  return inside;
}

double distance_to_footprint(const std::vector<Vec2>& ring, Vec2 p) {
  if (point_in_footprint(ring, p)) return 0.0;
  double best = HUGE_VAL;
  for (std::size_t i = 0, n = ring.size(); i < n; ++i) best = std::min(best, distance_to_segment(p, ring[i], ring[(i + 1) % n]));
  return best;
}

OpenSpace::OpenSpace(const Scene& scene)
    : scene_(&scene), bounds_(scene.bounds()), grid_(scene.buildings.empty() ? Box2{{0, 0}, {1, 1}} : bounds_.plan(), 32.0) {
  for (std::uint32_t i = 0; i < scene.buildings.size(); ++i) grid_.insert(plan_box(scene.buildings[i]), i);
}

bool OpenSpace::inside_building(Vec3 p) const {
  for (std::uint32_t i : grid_.query({{p.x, p.y}, {p.x, p.y}})) {
    const Building& b = scene_->buildings[i];
    if (p.z >= 0.0 && p.z <= b.height && point_in_footprint(b.footprint, plan(p))) return true;
  }
  return false;
}

bool OpenSpace::is_open(Vec2 p, double clearance) const {
  for (std::uint32_t i : grid_.query(grown({p, p}, clearance)))
    if (distance_to_footprint(scene_->buildings[i].footprint, p) <= clearance) return false;
  return true;
}

double OpenSpace::roof_height_near(Vec2 p, double radius) const {
  double top = 0.0;
  for (std::uint32_t i : grid_.query(grown({p, p}, radius))) {
    const Building& b = scene_->buildings[i];
    if (b.height > top && distance_to_footprint(b.footprint, p) <= radius) top = b.height;
  }
  return top;
}

Vec2 OpenSpace::nudge_to_open(Vec2 p, double clearance, double step) const {
  const double limit = std::max(p.x, bounds_.hi.x) + clearance + step;
  for (Vec2 q = p; q.x <= limit; q.x += step)
    if (is_open(q, clearance)) return q;
  return {limit + clearance, p.y};
}

}  // namespace cullcheck::generators
