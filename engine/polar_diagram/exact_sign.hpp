// Exact signs of the few plan-view determinants the polar diagram and its fan of rays need
// (Ortega et al.: "exact visibility in 2D scenes" only holds if every turn and every order is
// decided exactly; collinear walls and viewers on a wall's supporting line are the common case
// in a gridded city, not a rarity).
//
// Inputs are doubles; results are the exact signs of the real-number expressions. Each
// evaluates in double first with a forward error bound and falls back to expansion arithmetic
// (sums of products split exactly by fma) only when the bound cannot decide.
// The engine's own code: the oracle decides the same questions with CGAL's exact kernel.
#pragma once

#include "core/geometry.hpp"

namespace cullcheck::polar {

// sign((a - b) x (c - d)): +1 when c - d turns counter-clockwise from a - b.
int cross_sign(Vec2 a, Vec2 b, Vec2 c, Vec2 d);
// sign((a - b) . (c - d)).
int dot_sign(Vec2 a, Vec2 b, Vec2 c, Vec2 d);
// sign((b - a) x (c - a)): +1 when a, b, c turn counter-clockwise.
inline int orient(Vec2 a, Vec2 b, Vec2 c) { return cross_sign(b, a, c, a); }

}  // namespace cullcheck::polar
