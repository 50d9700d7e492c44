// Generated coordinates live on a 1 mm grid.
//
// Why: a generated scene is written as JSON with shortest round-trip numbers. Values computed
// through rotations carry long binary tails whose last bits could differ between maths
// libraries; rounding every coordinate and height to whole millimetres gives short, stable
// text ("12.345") and makes the same seed produce byte-identical files everywhere. 1 mm is far
// below any feature the culling methods model, and above every rounding error we introduce.
#pragma once

#include <cmath>
#include <cstdint>

#include "core/geometry.hpp"

namespace cullcheck::generators {

using Millimetres = std::int64_t;

// Exact: the nearest double to mm / 1000, so printing gives at most three decimals.
constexpr double metres(Millimetres mm) { return static_cast<double>(mm) / 1000.0; }
inline Millimetres to_mm(double m) { return std::llround(m * 1000.0); }
inline double snap_mm(double m) { return metres(to_mm(m)); }
inline Vec2 snap_mm(Vec2 p) { return {snap_mm(p.x), snap_mm(p.y)}; }

}  // namespace cullcheck::generators
