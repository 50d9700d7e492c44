// A terrain (design: "Scene model"): a regular height field over a rectangle of the plan,
// triangulated on its grid, for the radar application (thesis ch. 3.3). It is the ground, not
// an object: it has no id, and its triangles are numbered instead.
//
// Vertex (i, j) sits at corner + (i dx, j dy) with height z[j nx + i]: row 0 is the south edge,
// column 0 the west edge. Cell (i, j) of the grid (i < nx - 1, j < ny - 1) holds two
// triangles split along the diagonal from its south-west to its north-east corner, both
// counter-clockwise seen from above:
//   triangle 2 c     = (i, j), (i+1, j), (i+1, j+1)    (south-east half)
//   triangle 2 c + 1 = (i, j), (i+1, j+1), (i, j+1)    (north-west half)
// with c = j (nx - 1) + i. A vertex may be a hole (an elevation model's NoData kept as such):
// every triangle touching a hole is absent. A terrain every vertex of which is filled has no
// `hole` vector at all.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "core/geometry.hpp"

namespace cullcheck {

struct Terrain {
  Vec2 corner;                      // vertex (0, 0), scene-local metres
  double dx = 1.0, dy = 1.0;        // vertex spacing east and north, metres
  std::uint32_t nx = 0, ny = 0;     // vertices east and north, at least 2 each
  std::vector<double> z;            // nx * ny heights, metres, row-major from the south row
  std::vector<std::uint8_t> hole;   // empty, or nx * ny flags: 1 = no height (NoData kept)
  std::string source = "flat";      // what made it: a generator with its seed, or a file and what was done to it

  std::size_t vertex_count() const { return std::size_t(nx) * ny; }
  std::size_t cell_count() const { return std::size_t(nx - 1) * (ny - 1); }
  std::size_t triangle_count() const { return 2 * cell_count(); }  // present or not
  std::size_t index(std::uint32_t i, std::uint32_t j) const { return std::size_t(j) * nx + i; }
  bool is_hole(std::size_t v) const { return !hole.empty() && hole[v] != 0; }
  Vec3 vertex(std::uint32_t i, std::uint32_t j) const { return {corner.x + i * dx, corner.y + j * dy, z[index(i, j)]}; }
  // The vertex indices of triangle t, in the counter-clockwise order above.
  std::array<std::size_t, 3> triangle_vertices(std::size_t t) const;
  std::array<Vec3, 3> triangle(std::size_t t) const;
  bool triangle_present(std::size_t t) const;
  std::size_t present_triangle_count() const;
  // The extent of the grid in the plan and of its heights (holes left out).
  Box3 bounds() const;
  // The ground height under plan point p: the height of the triangle p falls in (on an edge,
  // either triangle's, which agree), or NaN outside the grid or over a hole.
  double height_at(Vec2 p) const;
};

// Throws InputError naming `where` when the grid is smaller than 2 x 2, a spacing is not a
// positive finite number, the heights or hole flags are not nx * ny long, a height that is no
// hole is not finite, or every vertex is a hole.
void validate(const Terrain& t, const std::string& where = "terrain");

}  // namespace cullcheck
