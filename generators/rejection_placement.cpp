#include "generators/rejection_placement.hpp"

#include "core/scene_io.hpp"
#include "generators/box_grid.hpp"

namespace cullcheck::generators {

void place_without_overlaps(Scene& scene, const PlacementLimits& limits, Random& rng,
                            const std::function<Candidate(Random&)>& make_candidate) {
  const double half = limits.area_size / 2;
  const Box2 area{{-half, -half}, {half, half}};
  BoxGrid occupied(area, limits.max_extent + limits.min_gap);
  for (int k = 0; k < limits.count; ++k) {
    for (int attempt = 0; attempt < limits.max_attempts; ++attempt) {
      Candidate c = make_candidate(rng);
      const Box2 box = bounds_of(c.footprint);
      if (box.lo.x < area.lo.x || box.lo.y < area.lo.y || box.hi.x > area.hi.x || box.hi.y > area.hi.y) continue;
      // Boxes at least min_gap apart (closed test on the grown box: touching is rejected too).
      if (occupied.any_intersects(grown(box, limits.min_gap))) continue;
      Building b;
      b.id = static_cast<ObjectId>(scene.buildings.size());
      b.footprint = std::move(c.footprint);
      b.height = c.height;
      validate_and_finish(b);
      occupied.insert(box, b.id);
      scene.buildings.push_back(std::move(b));
      break;
    }
  }
}

Vec2 draw_centre(Random& rng, double area_size) {
  const Millimetres half = to_mm(area_size / 2);
  return {metres(rng.uniform_int(-half, half)), metres(rng.uniform_int(-half, half))};
}

PlanarRotation draw_rotation(Random& rng, double rotated_fraction) {
  const bool free_angle = rng.bernoulli(rotated_fraction);
  const double t = free_angle ? rng.uniform_real(-1.0, 1.0) : 0.0;
  return rotation_from_half_tangent(t, static_cast<int>(rng.uniform_int(0, 3)));
}

}  // namespace cullcheck::generators
