// Occluder selection at a critical frame (section 5.3, Fig. 6): a best-first walk of the kd-tree
// by a priority φ (smaller first) that outputs the polygons of small nodes at least D from the
// eye until R polygons are chosen. Criteria: (i) fast, one pass over the top of the tree;
// (ii) R bounds the occluder count; (iii) the coverage priority favours nodes that cover image
// cells nothing chosen so far covers; (iv) nothing nearer than D, so that Eq. (1)'s δ, which
// grows with the nearest occluder's distance, buys time stamps that last.
//
// φ by distance: mindist(ξ, v), which chooses an annulus of inner radius D (Fig. 7a).
// φ by coverage: min over three sample cells of C(c), times mindist(ξ, v), where C(c) counts the
// chosen polygons over image cell c (each chosen node adds its polygon count spread over the
// cells its box covers) and the samples are the cells under the box's centre and under the two
// ends of its diagonal. C starts at 0, where the product is 0 for every node and says nothing;
// we order by (1 + C) mindist, which is the distance order until cells fill. C only grows, so a
// node's queued φ is a lower bound and is re-evaluated when it comes out (lazy update).
#pragma once

#include <cstdint>
#include <vector>

#include "engine/online_image_space/image_plane.hpp"
#include "engine/online_image_space/polygon_kd_tree.hpp"

namespace cullcheck::online {

enum class OccluderPriority : std::uint8_t { distance, coverage };

struct SelectionParameters {
  std::uint32_t occluders = 1000;     // R: polygons to choose
  double min_distance = 20.0;         // D, metres
  std::uint32_t node_polygons = 16;   // size(ξ) is "small" at or below this (leaves always are)
  OccluderPriority priority = OccluderPriority::coverage;
  int coverage_grid = 16;             // image cells each way for C(c)
};

struct OccluderSelection {
  std::vector<std::uint32_t> polygons;  // ascending
  double nearest = 0.0;                 // smallest distance from the eye to a chosen polygon's box
  std::uint64_t nodes_visited = 0;
};

OccluderSelection select_occluders(const PolygonKdTree& tree, const ScenePolygons& polygons, const ImagePlane& plane,
                                   const ViewVolume& volume, const SelectionParameters& parameters);

// Distance from `p` to the nearest point of `box` (0 inside).
double min_distance(Vec3 p, const Box3& box);

}  // namespace cullcheck::online
