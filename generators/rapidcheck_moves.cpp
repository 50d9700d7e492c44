// Bodies of the move generators declared in rapidcheck_moves.hpp (compiled once, as
// rapidcheck_gens.cpp explains).

#include "generators/rapidcheck_moves.hpp"

namespace cullcheck::generators::rcgen {

rc::Gen<Move> move() {
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

rc::Gen<std::vector<Move>> moves() {
  return rc::gen::mapcat(detail::int_in(1, 12), [](int n) { return rc::gen::container<std::vector<Move>>(n, move()); });
}

rc::Gen<Camera> level_street_camera(const Scene& scene) {
  return rc::gen::map(street_camera(scene), [](Camera c) {
    c.pitch = 0.0;
    c.roll = 0.0;
    return c;
  });
}

}  // namespace cullcheck::generators::rcgen
