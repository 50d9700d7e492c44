// Navigable regions (thesis ch. 5.1, Fig. 5.1): the street space of a generated city split into
// convex cells with an adjacency graph. Used as view cells for from-region PVSs
// (engine/shrinking/view_cell.hpp) and as the nodes of the VbAoI graph.
//
// Manhattan family (manhattan, plaza, default, thesis): one square cell per street crossing, one
// rectangle per street stretch between two crossings, and one cell per emptied plaza block.
// Neighbours share an edge. Ids are indices into the returned vector, in that order (crossings
// row by row, north-south stretches, east-west stretches, plaza blocks): deterministic.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/navigable_region.hpp"
#include "core/scene.hpp"
#include "generators/manhattan_layout.hpp"

namespace cullcheck::generators {

using cullcheck::NavigableRegion;

std::vector<NavigableRegion> street_cells(const ManhattanLayout& layout);
// The street cells of a scene made by a Manhattan-family generator (from its provenance);
// none for other generators and files.
std::optional<std::vector<NavigableRegion>> street_cells_of(const Scene& scene);

}  // namespace cullcheck::generators
