// The circle tiling of thesis Fig. 4.9d: where to centre the ε-discs whose from-region PVSs a
// walker uses, so that neighbouring discs overlap as little as possible and leave no hole.
//
// Discs of radius ε centred on a triangular (hexagonal) lattice of spacing √3·ε: the lattice's
// Voronoi cells are regular hexagons of circumradius ε, so every point of the plane lies within
// ε of its nearest centre (no hole, unlike Fig. 4.9c's spacing 2ε) while a disc overlaps each of
// its six neighbours only by a lens (unlike Fig. 4.9a-b's spacing ε). The lattice is anchored at
// the scene origin, so the same centres serve every walker and every view cell: a client can
// compute the PVS of the six neighbours of its disc ahead of time (ch. 4.1.2's prediction).
#pragma once

#include <cstdint>
#include <vector>

#include "core/geometry.hpp"

namespace cullcheck {

struct CircleTiling {
  double radius;  // ε

  double spacing() const { return std::sqrt(3.0) * radius; }  // between neighbouring centres
  double row_step() const { return 1.5 * radius; }            // between rows (y)
  // Centre (i, j): row j at y = j * row_step, x = (i + j/2) * spacing (odd rows shifted half).
  Vec2 centre(std::int64_t i, std::int64_t j) const {
    return {(static_cast<double>(i) + 0.5 * static_cast<double>(j & 1)) * spacing(), static_cast<double>(j) * row_step()};
  }
  // The centre nearest to p (ties to the lower index), at most ε away. Both functions throw
  // std::invalid_argument when a lattice index is not finite or beyond 2^53 (a NaN point, or
  // coordinates too large for ε).
  Vec2 nearest_centre(Vec2 p) const;
  // Every centre whose disc meets the convex counter-clockwise `ring`, row by row in serpentine
  // order (each centre follows a neighbour, so PVS decisions carry between them).
  std::vector<Vec2> centres_covering(const std::vector<Vec2>& ring) const;
};

// Distance from p to a convex counter-clockwise polygon (0 inside).
double distance_to_convex(const std::vector<Vec2>& ring, Vec2 p);

}  // namespace cullcheck
