// A mesh made of several closed solids that touch (a podium and its tower, a body and its roof, a
// CityJSON building's parts): which triangles belong to which solid, and which triangles lie
// inside the union (a face one solid shares with another that lies against it).
//
// Why: voxel erosion (voxel_erosion.hpp) takes every voxel a triangle touches as outside. At the
// face where a tower stands on its podium, that is a layer of "outside" voxels through the
// building, which erosion widens into a slot 2 ε high: the occluder leaks where the object is
// solid. The union's boundary is made of the faces that are not interior; a voxel none of those
// touches lies wholly inside or wholly outside the union.
//
// Where the coplanar triangles of other solids that face the other way (their outward normal
// against t's) cover a triangle t of solid A, A lies on one side of t and those solids on the
// other: that part of t is inside the union. Coverage is computed by subtracting those triangles
// from t in t's plane (convex pieces, double precision). t is interior when what is left has less
// than 1e-12 of t's area; partly interior when some but not all of it is covered (a podium's roof
// under its tower): then its boundary is the pieces left. Coplanar means each vertex within
// 1e-7 m of t's plane; a pair the tolerances miss stays a boundary face, which only costs tightness.
#pragma once

#include <cstdint>
#include <map>
#include <utility>
#include <vector>

#include "core/scene.hpp"

namespace cullcheck::slice_wise {

struct SolidParts {
  std::vector<std::uint32_t> part_of;  // per triangle: its solid (vertex-connected component), 0..parts-1
  std::uint32_t parts = 0;
  enum Cover : std::uint8_t { boundary, interior, partly };
  std::vector<Cover> cover;  // per triangle
  // Per partly interior triangle: the convex pieces of it left uncovered (3D polygons in its plane).
  std::map<std::uint32_t, std::vector<std::vector<Vec3>>> boundary_pieces;
  std::size_t interior_count = 0, partly_count = 0;
};

SolidParts solid_parts(const MeshObject& mesh);

// Which of several meshes lie against one another: the pairs (i < j, ascending) where a triangle of
// one and a triangle of the other lie in one plane (the same tolerances as above), face opposite
// ways and overlap with more than 1e-6 of the smaller one's area. A row of houses sharing party walls is
// such a chain; buildings that only meet at an edge or a corner are not. Only meshes whose boxes
// meet are compared, so a city of free-standing buildings costs one sweep over the boxes.
std::vector<std::pair<std::uint32_t, std::uint32_t>> touching_pairs(const std::vector<const MeshObject*>& meshes);

}  // namespace cullcheck::slice_wise
