// Occluder shrinking of general triangle meshes by an approximate Minkowski difference (slice
// paper §4.1.2-4.1.4): every vertex moves against its vertex normal far enough that every face
// moves inward by at least ε, and faces whose movement volumes collide are dropped.
//
// The rule, per vertex v with the distinct unit normals N_i of the faces around it and the vertex
// normal N_v (their normalised sum):
//   α/2 = min_i (90° - angle(N_v, N_i)),   δ = ε / sin(α/2),   v' = v - δ N_v.
// Why every face moves at least ε: face i's plane is crossed by v' at depth δ cos(angle(N_v, N_i))
// = ε cos(angle_i) / cos(max_j angle_j) >= ε; depth is affine over a triangle, so the whole moved
// triangle lies at least ε behind its original plane. This is Theorem 1's premise (if every face
// moves at least ε, visibility from the view cell's centre against the shrunk occluder holds for
// every viewpoint within ε of it). The premise is necessary, not sufficient, for a non-convex mesh:
// far-apart faces may pass through one another; that is what the movement-volume test removes.
//
// Policies (tolerances are explicit; nothing here is exact arithmetic):
//  - Distinct normals: two face normals are the same plane direction when their unit vectors'
//    dot product exceeds 1 - 1e-12. A flat roof split into a fan must not count several times:
//    a repeated normal tilts N_v towards that plane and makes δ (and every other face's motion)
//    larger than the geometry needs; with deduplication a box corner moves by exactly (ε, ε, ε).
//  - Ground vertices (|z - ground_z| <= 1e-9 m): the viewer never goes below the ground, so such a
//    vertex moves horizontally only (Fig. 16). Dropping the vertical part of -δ N_v leaves vertical
//    walls' motion unchanged but can take a sloped face's motion below ε, so δ is recomputed with
//    the horizontal part of N_v in place of N_v (same formula over the vertex's non-floor faces):
//    every incident non-floor face then still moves at least ε. Floor faces (every vertex on the
//    ground) are not required to move and are left out of the vertex normal.
//  - A vertex whose faces' normals span a hemisphere or more (some angle(N_v, N_i) >= 90° - 1e-9
//    rad) has no finite δ: it does not move and every face around it is removed.
//  - Neighbours (faces sharing a vertex or an edge) are never tested against each other: their
//    movement volumes always share the common vertices' motion, and the common vertex moves one way
//    for both faces so they stay joined (the paper's Fig. 14a). Only faces with no common vertex
//    are tested, first by bounding boxes, then by a separating-axis test between the two convex
//    hulls (each hull: original triangle plus moved triangle, six points). Hulls that merely touch
//    (overlap no deeper than 1e-9 times the hulls' extent) count as separated. Both faces of a
//    colliding pair are removed.
//  - Removed too: moved triangles of (near) zero area (|cross| <= 1e-12 times the squared extent)
//    and moved triangles that turned over (moved normal opposite the original), which the paper's
//    "bad cases" cover in words only.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/geometry.hpp"
#include "core/scene.hpp"

namespace cullcheck {

// A plain triangle mesh: triangles are counter-clockwise seen from outside, so the outward normal
// of triangle t is normalized(cross(b - a, c - a)).
struct TriangleMesh {
  std::vector<Vec3> vertices;
  std::vector<std::array<std::uint32_t, 3>> triangles;

  Vec3 normal(std::size_t t) const;  // outward unit normal ({0,0,0} for a zero-area triangle)
};

struct MeshShrinkStatistics {
  std::size_t faces_in = 0;
  std::size_t faces_removed = 0;  // the four counts below
  std::size_t collisions_removed = 0;
  std::size_t zero_area_removed = 0;
  std::size_t flipped_removed = 0;
  std::size_t unshrinkable_removed = 0;  // faces around a vertex with no finite δ
  std::size_t pairs_tested = 0;          // non-neighbour pairs whose boxes overlapped
  std::size_t degenerate_dropped = 0;    // zero-area in the input: dropped, not counted as removed
  double max_delta = 0.0;                // largest vertex displacement
};

struct ShrunkMesh {
  // Same vertex indices as the input, at their moved positions; only the kept triangles.
  TriangleMesh mesh;
  std::vector<double> delta;  // per vertex: distance moved
  MeshShrinkStatistics stats;
};

ShrunkMesh shrink_mesh(const TriangleMesh& mesh, double epsilon, double ground_z = 0.0);

// The closed (floorless, as in Building::triangle_count) mesh of a building. With n footprint
// vertices: vertices [0, n) are the footprint at z = 0, [n, 2n) the same at the roof; triangles
// are two per wall (wall i joins footprint vertices i and i + 1, triangles 2i and 2i + 1), then a
// fan over each convex prism's ring on the roof.
TriangleMesh building_mesh(const Building& building);

}  // namespace cullcheck
