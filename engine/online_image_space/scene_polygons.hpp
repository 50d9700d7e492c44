// The polygons on-line image-space culling works with (Wang, Agarwal & Har-Peled 2001, section 4:
// "S, the set of input polygons"). A building gives one quadrangle per footprint edge (its walls)
// and one convex polygon per convex vertical prism top (its roof); a mesh object gives its
// triangles. Every polygon is convex, which the occluder rasteriser relies on, and knows the
// object it belongs to: the method sends polygons, and an object is in the PVS when any of its
// polygons is sent.
#pragma once

#include <cstdint>
#include <vector>

#include "core/geometry.hpp"
#include "core/scene.hpp"

namespace cullcheck::online {

struct ScenePolygons {
  std::vector<Vec3> vertices;         // every polygon's vertices, one after the other
  std::vector<std::uint32_t> first;   // polygon p's vertices are [first[p], first[p + 1])
  std::vector<std::uint32_t> object;  // index into `ids` of the polygon's object
  std::vector<Box3> box;              // smallest orthogonal box of each polygon (B_Δ)
  std::vector<ObjectId> ids;          // object ids, by object index: buildings, then meshes

  std::size_t size() const { return object.size(); }
  std::uint32_t vertex_count(std::size_t p) const { return first[p + 1] - first[p]; }
  const Vec3* polygon(std::size_t p) const { return vertices.data() + first[p]; }
  // p_Δ: the xy-projection of the bottom-left corner of B_Δ, the point the kd-tree stores.
  Vec2 anchor(std::size_t p) const { return {box[p].lo.x, box[p].lo.y}; }
};

// Walls (zero-length footprint edges skipped), roofs and mesh triangles (degenerate ones skipped).
ScenePolygons scene_polygons(const Scene& scene);

// The polygons of one object, appended to `out` with object index `object` (dynamic insertion).
void append_building(const Building& b, std::uint32_t object, ScenePolygons& out);
void append_mesh(const MeshObject& m, std::uint32_t object, ScenePolygons& out);

}  // namespace cullcheck::online
