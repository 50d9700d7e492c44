#include "core/convex_partition.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Partition_traits_2.h>
#include <CGAL/partition_2.h>

#include <iterator>
#include <list>

namespace cullcheck {

std::vector<std::vector<Vec2>> convex_partition(const std::vector<Vec2>& ring) {
  // Exact predicates, inexact constructions: the partition only reuses input vertices, so no
  // new coordinates are constructed and the pieces are exactly convex in the input coordinates.
  using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
  using Traits = CGAL::Partition_traits_2<Kernel>;
  using Polygon = Traits::Polygon_2;
  std::vector<Traits::Point_2> points;
  points.reserve(ring.size());
  for (Vec2 p : ring) points.emplace_back(p.x, p.y);
  std::list<Polygon> pieces;
  CGAL::approx_convex_partition_2(points.begin(), points.end(), std::back_inserter(pieces), Traits());
  std::vector<std::vector<Vec2>> out;
  out.reserve(pieces.size());
  for (const Polygon& piece : pieces) {
    std::vector<Vec2> r;
    for (auto v = piece.vertices_begin(); v != piece.vertices_end(); ++v) r.push_back({v->x(), v->y()});
    out.push_back(std::move(r));
  }
  return out;
}

}  // namespace cullcheck
