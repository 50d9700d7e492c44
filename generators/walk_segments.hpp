// The segments a pedestrian walk is made of, and which one comes next: shared by the grid walk
// (street_walk.cpp) and the free-space walk (free_space_walk.cpp), so both draw their segments
// alike (one draw per segment, the same stream as before it was shared).
#pragma once

#include "generators/camera_paths.hpp"
#include "generators/random.hpp"

namespace cullcheck::generators {

enum class WalkKind { forward, backward, sidestep, stop };

struct WalkSegment {
  WalkKind kind;
  int frames = 0;       // forward, backward, stop
  double metres = 0.0;  // sidestep: signed, positive to the left
};

// Two draws: the kind, weighted by the parameters' forward, backward, sidestep and stop weights,
// then its length (30-240 frames forward, 10-60 back, 15-60 stopped, a sidestep within
// ±sidestep_reach metres).
inline WalkSegment next_walk_segment(const StreetWalkParams& p, Random& rng, double sidestep_reach) {
  const double weights[4] = {p.forward_weight, p.backward_weight, p.sidestep_weight, p.stop_weight};
  const double total = weights[0] + weights[1] + weights[2] + weights[3];
  double pick = rng.uniform01() * total;
  int kind = 0;
  while (kind < 3 && (weights[kind] == 0.0 || pick >= weights[kind])) pick -= weights[kind], ++kind;
  WalkSegment s{static_cast<WalkKind>(kind)};
  switch (s.kind) {
    case WalkKind::forward: s.frames = static_cast<int>(rng.uniform_int(30, 240)); break;
    case WalkKind::backward: s.frames = static_cast<int>(rng.uniform_int(10, 60)); break;
    case WalkKind::sidestep: s.metres = rng.uniform_real(-sidestep_reach, sidestep_reach); break;
    case WalkKind::stop: s.frames = static_cast<int>(rng.uniform_int(15, 60)); break;
  }
  return s;
}

}  // namespace cullcheck::generators
