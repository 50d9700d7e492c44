// A navigable region (design: "Scene model"; thesis ch. 5.1, Fig. 5.1): a convex piece of the
// street space that users walk on, with the regions it shares an edge with. Generators make them
// (generators/street_cells.hpp); the VbAoI graph (engine/vbaoi/) turns each into a node.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/geometry.hpp"
#include "core/random.hpp"

namespace cullcheck {

struct NavigableRegion {
  std::uint32_t id = 0;
  std::string kind;              // "crossing", "street", "plaza", "free"
  std::vector<Vec2> ring;        // convex, counter-clockwise
  std::vector<std::uint32_t> neighbours;  // sorted ids of the regions sharing an edge
};

// The overlap of two convex rings' boundaries, when it has positive length: the edge a walker
// crosses from one region to the other. Edges are compared for collinearity within `tolerance`
// metres.
std::optional<std::pair<Vec2, Vec2>> shared_edge(const std::vector<Vec2>& a, const std::vector<Vec2>& b,
                                                 double tolerance = 1e-6);

// Whether `point` lies in the convex counter-clockwise `ring`, admitting points up to `tolerance`
// metres outside it.
bool ring_contains(const std::vector<Vec2>& ring, Vec2 point, double tolerance = 1e-9);

// A uniform point of the convex `ring`: rejection in its bounding box, up to 64 draws, then the
// vertices' mean (only a sliver of a ring gets that far).
Vec2 random_point_in(const std::vector<Vec2>& ring, Random& rng);

// The first region (by id) containing `point` within `tolerance`; -1 when none.
std::int64_t locate_region(const std::vector<NavigableRegion>& regions, Vec2 point, double tolerance = 1e-9);

}  // namespace cullcheck
