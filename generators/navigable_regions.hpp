// Navigable regions of any scene (design: "Scene model"; thesis ch. 5.1, Fig. 5.1): the open
// ground split into convex cells with an adjacency graph, the nodes of the VbAoI graph.
//
//  - Manhattan family (manhattan, plaza, default, thesis): the street cells of street_cells.hpp
//    (a cell per crossing, per street stretch, per plaza block).
//  - Every other scene (irregular, scatter, kept cases, scene files): free_space_cells below.
#pragma once

#include <vector>

#include "core/navigable_region.hpp"
#include "core/scene.hpp"

namespace cullcheck::generators {

struct FreeSpaceOptions {
  double margin = 20.0;           // open ground kept around the scene's plan bounds, metres
  double cell_size = 25.0;        // cells never reach across the lines of a grid this fine, metres
};

// The open ground of the scene's plan bounds grown by `margin`, minus every footprint, as convex
// cells: a constrained Delaunay triangulation (CGAL, exact predicates) whose constrained edges
// are every footprint wall and the lines of a square grid of side cell_size, its triangles in the
// open merged greedily across their longest shared edges while the union stays strictly convex
// (exact orientation tests on the vertices' doubles). So each cell lies in one grid square, and
// open ground away from buildings is the squares themselves. Cells have kind "free", ids in a
// canonical order (by their vertices), neighbours sharing an edge of positive length. Vertices
// are footprint and bounds corners, and where a grid line crosses a wall, that crossing
// (constructed in doubles: the wall there may bend by a rounding error).
// Throws InputError (object "navigable regions") when the options are out of range.
std::vector<NavigableRegion> free_space_cells(const Scene& scene, const FreeSpaceOptions& options = {});

// The scene's navigable regions: street cells for the Manhattan family, free-space cells for the
// rest. `options` applies to free-space cells only.
std::vector<NavigableRegion> navigable_regions(const Scene& scene, const FreeSpaceOptions& options = {});

}  // namespace cullcheck::generators
