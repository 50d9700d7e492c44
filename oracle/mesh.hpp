// The scene as one triangle mesh, the form the ray oracle hands to Embree.
//
// The scene's OBJECTS are its buildings followed by its mesh objects: object index k < building
// count is Scene::buildings[k], any other is Scene::meshes[k - building count]. Each building
// contributes its walls (two triangles per footprint edge, z = 0 to height) and its roof: the
// oracle's own triangulation of the footprint (roof_triangulation.hpp, a CGAL constrained
// triangulation; not core's convex prisms, which the engine uses), exactly footprint.size() - 2
// triangles, after the walls. No floor: nothing
// is seen from below the ground plane. Each mesh object contributes its triangles as they are
// (two-sided: Embree's triangles are hit from either side). Triangle i belongs to object
// owner_index[i], whose stable id is owner_id[i] (= object_ids[owner_index[i]]).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "core/geometry.hpp"
#include "core/scene.hpp"

namespace cullcheck::oracle {

// An edge of a mesh object: its end points and the triangles (indices into the object's own
// triangles) that have it; one triangle for a boundary edge, three or more where the mesh is not
// a manifold.
struct MeshEdge {
  Vec3 a, b;
  std::vector<std::uint32_t> triangles;
};

// The edges of a mesh object, in the order its triangles first name them.
std::vector<MeshEdge> mesh_edges_of(const MeshObject& m);

struct TriangleMesh {
  // Vertices in scene-local metres (double). Embree receives them as floats relative to
  // `origin`, a whole-metre point near the scene's centre, so single precision is spent on the
  // scene's extent rather than on its distance from (0, 0).
  Vec3 origin;
  std::vector<Vec3> vertices;
  std::vector<std::array<std::uint32_t, 3>> triangles;
  std::vector<std::uint32_t> owner_index;  // primID -> object index (buildings, then meshes)
  std::vector<ObjectId> owner_id;          // primID -> the object's id
  std::vector<ObjectId> object_ids;        // object index -> id
  std::vector<std::uint32_t> first_triangle;  // object index -> its first primID (its triangles are contiguous, in order)
  std::size_t building_count = 0;          // objects [0, building_count) are buildings
  // Per building: its roof triangles as indices into its footprint (roof_triangulation.hpp).
  std::vector<std::vector<std::array<std::uint32_t, 3>>> roofs;
  // Per mesh object (Scene::meshes[k]): its edges, for the rays that graze its silhouette
  // (ray_plan.hpp). Vertices equal in position count as one, so a mesh whose triangles do not
  // share indices (as glTF files often store them) still has its inner edges.
  std::vector<std::vector<MeshEdge>> mesh_edges;
};

// Embree's index buffers are 32-bit and the merged mesh shares no vertex, so it holds at most
// this many triangles (three vertex indices each, the largest 2^32 - 1).
inline constexpr std::size_t kMaxMergedTriangles = 0xFFFFFFFFull / 3;  // 1,431,655,765
// InputError("scene", "triangles") when a scene of `triangles` triangles would not fit: a larger
// scene is refused, never given wrapped indices. triangulate() checks it first.
void check_merged_triangle_count(std::size_t triangles);

// Throws InputError naming the building when its footprint cannot be triangulated (not simple).
TriangleMesh triangulate(const Scene& scene);

}  // namespace cullcheck::oracle
