// The visible set from a point over an angular interval, in the plan view, by a fan of rays
// (Ortega, Rueda and Feito, section 4), exact.
//
// The interval is cut at the axes; each piece lies in one quadrant and is swept in that
// quadrant's polar diagram's sense (Fig. 3: East+ counter-clockwise from east, West-
// clockwise from west, West+ counter-clockwise from west, East- clockwise from east). Where a
// piece starts on an axis, the viewer is located in that diagram first (step 1): the vertex it
// names is the first direction that meets any building, so the empty directions before it cost
// nothing. Then rays (step 2): each ray meets one edge first; the next ray goes to that edge's
// far end (a tangent ray when the edge ends a silhouette), unless something stands in front of
// the edge between the two rays. The paper detects such a missed object (Fig. 5) by comparing
// the lists of polar edges the two rays cross, using its reference [10]'s collision algorithm,
// which the paper does not give. This fan certifies each wedge exactly instead: the triangle
// between the eye, the first ray's hit and the edge's far end must hold no vertex (a vertex
// grid answers it); when it holds some, the next ray goes to the angularly first of them, so
// the angular interval is split where the missed object begins.
//
// Exact in the regularized sense the oracle uses (oracle/exact_2d.hpp): a building is visible
// when the directions whose first hit lies on it form a set of positive angle. Every side and
// order is decided by exact_sign.hpp; rays between two critical directions are handled
// symbolically (the ray "just after" a direction), so collinear walls, touching buildings and
// eyes on a wall's supporting line need no tolerance.
//
// Preconditions: the eye lies outside every footprint and strictly inside the frame (the scene's
// bounds grown by a margin); footprints do not overlap (they may touch).
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "core/camera.hpp"
#include "core/scene.hpp"
#include "engine/polar_diagram/polar_diagram.hpp"

namespace cullcheck::polar {

// A horizontal view: the directions counter-clockwise from `right` to `left` (unit vectors), or
// every direction.
struct PlanWedge {
  bool everything = true;
  Vec2 right{1.0, 0.0};
  Vec2 left{1.0, 0.0};
};
PlanWedge plan_wedge(const Camera& camera);

struct FanOptions {
  bool polar_start = true;      // step 1: locate the eye in a polar diagram where a piece starts on an axis
  bool certify_wedges = true;   // false: trust each edge up to its far end (a straw man the property must catch)
};

struct FanStatistics {
  std::uint64_t rays = 0;              // rays shot (the paper's O(2k))
  std::uint64_t polar_locates = 0;     // eye located in a polar diagram
  std::uint64_t polar_skips = 0;       // empty starts skipped by a polar location
  std::uint64_t wedge_splits = 0;      // wedges split because a vertex stood in front (Fig. 5)
  std::uint64_t vertices_tested = 0;   // vertices tested exactly by wedge certificates
  std::uint64_t edges_tested = 0;      // edges tested exactly by rays
  std::uint64_t cells_walked = 0;      // grid cells walked by rays and scanned by certificates
};

struct FanResult {
  std::vector<ObjectId> visible;             // sorted building ids
  std::vector<std::uint32_t> visible_edges;  // sorted edge indices (VisibilityFan::edge)
  FanStatistics stats;
};

class VisibilityFan {
 public:
  explicit VisibilityFan(const Scene& scene, FanOptions options = {});
  ~VisibilityFan();
  VisibilityFan(const VisibilityFan&) = delete;
  VisibilityFan& operator=(const VisibilityFan&) = delete;

  // One query at a time per object (queries share scratch marks). Throws std::invalid_argument
  // when the eye lies outside the frame.
  FanResult visible(Vec2 eye, const PlanWedge& wedge) const;

  struct Edge {
    std::uint32_t a, b;     // vertex indices
    std::uint32_t object;   // building index, or kFrame
  };
  static constexpr std::uint32_t kFrame = 0xffffffffu;
  const Edge& edge(std::uint32_t i) const { return edges_[i]; }
  const std::vector<Vec2>& vertices() const { return points_; }
  const PolarDiagrams& diagrams() const { return diagrams_; }
  const Box2& frame() const { return frame_; }
  // Whether `eye` lies strictly inside the frame (queries need it).
  bool inside_frame(Vec2 eye) const {
    return eye.x > frame_.lo.x && eye.x < frame_.hi.x && eye.y > frame_.lo.y && eye.y < frame_.hi.y;
  }
  std::size_t building_vertices() const { return building_vertices_; }

 private:
  struct Dir {  // the direction of a - b from the eye
    Vec2 a, b;
  };
  struct Piece {
    Dir start, end;
    int sense;   // +1 counter-clockwise, -1 clockwise
    int diagram; // DiagramKind to locate in when `start` is that diagram's axis, else -1
  };
  struct Scratch;

  std::vector<Piece> pieces(const PlanWedge& wedge) const;
  void sweep(Vec2 eye, const Piece& piece, Scratch& s, FanResult& out) const;
  int side(const Dir& d, Vec2 x, Vec2 eye, int sense) const;
  bool crosses_after(std::uint32_t e, const Dir& d, Vec2 eye, int sense) const;
  bool nearer(std::uint32_t e1, std::uint32_t e2, Vec2 eye) const;
  std::uint32_t shoot(Vec2 eye, const Dir& d, int sense, Scratch& s, FanResult& out) const;
  std::int64_t first_in_front(Vec2 eye, const Dir& cur, std::uint32_t hit, std::uint32_t far_end, int sense,
                              FanResult& out) const;
  std::uint32_t far_end(std::uint32_t e, const Dir& d, Vec2 eye, int sense) const;

  // A uniform grid over the frame: the edges meeting each cell (bounding boxes, padded) and the
  // vertices in it.
  struct Grid {
    Vec2 origin;
    double cell = 1.0;
    int nx = 1, ny = 1;
    std::vector<std::uint32_t> edge_begin, edge_items, vertex_begin, vertex_items;
    int cx(double x) const;
    int cy(double y) const;
  };

  FanOptions options_;
  std::vector<Vec2> points_;                 // building vertices, then the frame's four corners
  std::vector<std::uint32_t> point_object_;  // building index or kFrame
  std::vector<Edge> edges_;
  std::vector<ObjectId> ids_;                // building index -> id
  std::size_t building_vertices_ = 0;
  Box2 frame_;
  Grid grid_;
  PolarDiagrams diagrams_;
  std::unique_ptr<Scratch> scratch_;
};

}  // namespace cullcheck::polar
