// Placement without overlaps for the scatter and irregular cities: candidates are drawn one at a
// time and accepted only if their bounding box, grown by the minimum gap, meets no box already
// placed (BoxGrid). Deterministic: candidates come from one seeded stream in a fixed order, and
// the number of attempts is bounded, so a crowded area yields fewer buildings, never a hang.
#pragma once

#include <functional>
#include <optional>

#include "core/scene.hpp"
#include "generators/footprint_shapes.hpp"
#include "generators/random.hpp"

namespace cullcheck::generators {

struct Candidate {
  Ring footprint;  // world coordinates, on the 1 mm grid
  double height = 0.0;
};

struct PlacementLimits {
  int count = 0;             // buildings wanted
  int max_attempts = 50;     // candidates per building before that building is skipped
  double area_size = 0.0;    // the square [-area/2, area/2]^2 must contain every footprint
  double min_gap = 0.0;      // least distance between bounding boxes
  double max_extent = 0.0;   // largest bounding-box side a candidate can have (sizes the grid)
};

// Appends accepted candidates to scene.buildings with ids continuing from its size, each passed
// through validate_and_finish.
void place_without_overlaps(Scene& scene, const PlacementLimits& limits, Random& rng,
                            const std::function<Candidate(Random&)>& make_candidate);

// A uniformly drawn centre on the 1 mm grid inside the square of side area_size.
Vec2 draw_centre(Random& rng, double area_size);

// A rotation: with probability rotated_fraction a free angle, else one of the four axis
// directions (exact, so axis-aligned footprints keep whole-millimetre coordinates).
PlanarRotation draw_rotation(Random& rng, double rotated_fraction);

}  // namespace cullcheck::generators
