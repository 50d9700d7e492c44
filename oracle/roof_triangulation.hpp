// The oracle's own roofs (design: "Independence": the oracle does not build roofs from the
// convex prisms core/ hands the engine, so a bad partition cannot hide in both).
//
// A building's roof is its footprint polygon at the building's height, triangulated here by a
// CGAL constrained Delaunay triangulation of the footprint's edges (exact predicates, Epick: no
// point is constructed, every triangle corner is a footprint vertex). The triangles kept are the
// faces of nesting level 1 (inside the footprint boundary, reached by crossing it once from the
// infinite face), so they cover the footprint exactly once: their areas sum to its area and none
// lies outside it. A simple polygon of n vertices gives n - 2 triangles.
//
// CGAL is compiled in roof_triangulation.cpp only (an object library, like exact_2d.cpp).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "core/geometry.hpp"

namespace cullcheck::oracle {

// Triangles as indices into `footprint`, each counter-clockwise seen from above. Throws
// std::invalid_argument when the footprint has fewer than 3 vertices, repeats a vertex or is not
// simple (the triangulation would not cover it exactly once).
std::vector<std::array<std::uint32_t, 3>> triangulate_roof(const std::vector<Vec2>& footprint);

}  // namespace cullcheck::oracle
