// Convex decomposition of a simple counter-clockwise polygon into counter-clockwise convex
// pieces, used to turn non-convex footprints into CVPs. Backed by CGAL's Hertel-Mehlhorn
// approximate convex partition (at most four times the optimal piece count), kept in one
// translation unit so CGAL's headers are compiled once.
#pragma once

#include <vector>

#include "core/geometry.hpp"

namespace cullcheck {

std::vector<std::vector<Vec2>> convex_partition(const std::vector<Vec2>& ring);

}  // namespace cullcheck
