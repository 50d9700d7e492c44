// Polar diagrams of a plan-view scene (Ortega, Rueda and Feito, sections 2-3).
//
// The East+ polar diagram partitions the plane by which object a ray from a point meets first
// when it turns counter-clockwise from due east (the smallest "polar angle" in [0, pi)). East-
// turns clockwise from east, West+ counter-clockwise from west, West- clockwise from west; each
// covers one quadrant of directions (Fig. 3). All four are the East+ diagram of the scene
// reflected: East- mirrors y, West+ turns the plane by pi, West- mirrors x (sign flips, exact).
//
// What is stored. Away from the horizontal "shadow" strips (points whose due-east ray already
// meets an object, polar angle 0), a point's region is decided by the vertices above it: its
// owner holds the vertex of smallest polar angle, which is the tangent point from the query
// point to the convex hull of the vertices above it. The diagram is kept as that point-location
// structure rather than as explicit region edges: vertices sorted by height, a segment tree over
// them, and in each node the right-hand convex chain of its vertices. Construction is one sort
// and linear chains per level, O(n log n) time and space; locating a point is O(log^2 n) exact
// orientation tests. The region's edges (lines through vertex pairs and horizontals through
// vertices, section 2) are never built, so no crossed-edge lists exist; the fan of rays
// (visibility_fan.hpp) certifies its wedges another way.
#pragma once

#include <cstdint>
#include <vector>

#include "core/geometry.hpp"
#include "core/scene.hpp"

namespace cullcheck::polar {

enum class DiagramKind : std::uint8_t { east_plus, east_minus, west_plus, west_minus };
const char* to_string(DiagramKind kind);

class PolarDiagram {
 public:
  PolarDiagram(const std::vector<Vec2>& vertices, DiagramKind kind);

  // The vertex a ray from `p` meets first when it turns in the diagram's sense from its axis,
  // among vertices strictly on the turning side of the axis line (above p for East+); equal
  // angles go to the nearer vertex. -1 when there is none. Objects the axis ray itself meets
  // (polar angle 0) are the caller's: the fan shoots that ray anyway.
  std::int64_t first_vertex(Vec2 p) const;

  DiagramKind kind() const { return kind_; }
  std::size_t chain_vertices() const { return chains_.size(); }  // stored over all tree nodes

 private:
  Vec2 local(Vec2 v) const;  // into the East+ frame
  std::uint32_t candidate(std::size_t node, Vec2 p) const;

  DiagramKind kind_;
  std::vector<Vec2> sorted_;              // local coordinates, by (y, x) descending
  std::vector<std::uint32_t> original_;   // sorted_ index -> caller's vertex index
  std::size_t leaves_ = 1;                // segment tree over sorted_, a power of two
  std::vector<std::uint32_t> chain_begin_, chain_end_;  // per node, into chains_
  std::vector<std::uint32_t> chains_;     // sorted_ indices, each chain from low to high
};

// Every building's footprint vertices, building by building in the scene's order: the points the
// diagrams are built on.
std::vector<Vec2> footprint_vertices(const Scene& scene);

// The four diagrams of one scene's vertices, built once.
struct PolarDiagrams {
  explicit PolarDiagrams(const std::vector<Vec2>& vertices);
  const PolarDiagram& of(DiagramKind kind) const { return diagrams[static_cast<int>(kind)]; }
  std::vector<PolarDiagram> diagrams;
};

}  // namespace cullcheck::polar
