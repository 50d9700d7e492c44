// The segments a pedestrian walk is made of, and which one comes next: shared by the grid walk
// (street_walk.cpp) and the free-space walk (free_space_walk.cpp), so both draw their segments
// alike (one draw per segment, the same stream as before it was shared).
#pragma once

#include "generators/camera_paths.hpp"
#include "generators/random.hpp"

namespace cullcheck::generators {

enum class WalkSegment { forward, backward, sidestep, stop };

// One draw, weighted by the parameters' forward, backward, sidestep and stop weights.
inline WalkSegment next_walk_segment(const StreetWalkParams& p, Random& rng) {
  const double weights[4] = {p.forward_weight, p.backward_weight, p.sidestep_weight, p.stop_weight};
  const double total = weights[0] + weights[1] + weights[2] + weights[3];
  double pick = rng.uniform01() * total;
  int kind = 0;
  while (kind < 3 && (weights[kind] == 0.0 || pick >= weights[kind])) pick -= weights[kind], ++kind;
  return static_cast<WalkSegment>(kind);
}

}  // namespace cullcheck::generators
