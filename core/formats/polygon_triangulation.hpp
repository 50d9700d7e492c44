// Triangles of a planar polygon with holes given in 3D (a CityJSON surface: an outer ring and
// inner rings of vertex indices). CGAL's constrained Delaunay triangulation in the plane the
// polygon faces most (this file's .cpp is the formats library's only CGAL translation unit).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/geometry.hpp"

namespace cullcheck::formats {

// Triangles as index triples into `vertices`, facing the way the outer ring turns (Newell's
// normal). Where rings cross, the triangulation adds a vertex: it is lifted onto the polygon's
// plane and appended to `vertices`. Empty when the outer ring spans no area.
std::vector<std::array<std::uint32_t, 3>> triangulate_polygon(std::vector<Vec3>& vertices,
                                                              const std::vector<std::vector<std::size_t>>& rings);

}  // namespace cullcheck::formats
