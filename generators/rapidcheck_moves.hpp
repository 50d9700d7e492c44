// RapidCheck generators of camera paths made of pathological moves (camera_moves.hpp), for the ΔH properties
// (thesis ch. 3.1.3, Table 3.1 and Fig. 3.10): lateral steps past thin buildings, steps larger
// than a building is wide, forward and backward steps, turns (across the 0/2π azimuth wrap on
// purpose), stops (the same camera again) and jumps in height. A path is a start camera and a
// list of moves, so RapidCheck shrinks it to fewer, smaller moves.
//
// Link target: cullcheck_generators_rc (bodies in rapidcheck_moves.cpp).
#pragma once

#include <rapidcheck.h>

#include <ostream>
#include <vector>

#include "core/camera.hpp"
#include "core/camera_path.hpp"
#include "generators/angles.hpp"
#include "generators/camera_moves.hpp"
#include "generators/rapidcheck_gens.hpp"

namespace cullcheck::generators {

inline void showValue(const Move& m, std::ostream& os) { os << to_string(m.kind) << " " << m.amount; }

namespace rcgen {

// One move. Step sizes: a pedestrian's frame (5 cm), a run (0.5 m) or a jump past a building
// (1-12 m, more than a thin slab is wide); turns up to 45 degrees either way; rises up to 3 m.
rc::Gen<Move> move();

// 1-12 moves.
rc::Gen<std::vector<Move>> moves();

// A start camera at street level, level (pitch and roll 0: the ΔH failure is about the plan
// view), facing along an axis or near the azimuth wrap on purpose, with an ordinary or
// 360-degree field of view.
rc::Gen<Camera> level_street_camera(const Scene& scene);

}  // namespace rcgen
}  // namespace cullcheck::generators
