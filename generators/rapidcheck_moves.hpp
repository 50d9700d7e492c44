// RapidCheck generators of camera paths made of pathological moves (camera_moves.hpp), for the ΔH properties
// (thesis ch. 3.1.3, Table 3.1 and Fig. 3.10): lateral steps past thin buildings, steps larger
// than a building is wide, forward and backward steps, turns (across the 0/2π azimuth wrap on
// purpose), stops (the same camera again) and jumps in height. A path is a start camera and a
// list of moves, so RapidCheck shrinks it to fewer, smaller moves.
//
// Link target: cullcheck_generators_rc.
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
inline rc::Gen<Move> move() {
  using detail::int_in;
  const auto length = rc::gen::weightedOneOf<double>({{2, rc::gen::just(0.05)},
                                                      {2, rc::gen::just(0.5)},
                                                      {3, rc::gen::map(int_in(1, 12), [](int m) { return double(m); })}});
  auto step = [length](MoveKind k) {
    return rc::gen::map(length, [k](double a) { return Move{k, a}; });
  };
  return rc::gen::weightedOneOf<Move>(
      {{2, step(MoveKind::forward)},
       {1, step(MoveKind::backward)},
       {4, step(MoveKind::left)},
       {4, step(MoveKind::right)},
       {2, rc::gen::map(detail::signed_grid(450, radians(0.1)), [](double a) { return Move{MoveKind::turn, a}; })},
       {1, rc::gen::just(Move{MoveKind::stop, 0.0})},
       {1, rc::gen::map(detail::signed_grid(30, 0.1), [](double a) { return Move{MoveKind::rise, a}; })}});
}

// 1-12 moves.
inline rc::Gen<std::vector<Move>> moves() {
  return rc::gen::mapcat(detail::int_in(1, 12), [](int n) { return rc::gen::container<std::vector<Move>>(n, move()); });
}

// A start camera at street level, level (pitch and roll 0: the ΔH failure is about the plan
// view), facing along an axis or near the azimuth wrap on purpose, with an ordinary or
// 360-degree field of view.
inline rc::Gen<Camera> level_street_camera(const Scene& scene) {
  return rc::gen::map(street_camera(scene), [](Camera c) {
    c.pitch = 0.0;
    c.roll = 0.0;
    return c;
  });
}

}  // namespace rcgen
}  // namespace cullcheck::generators
