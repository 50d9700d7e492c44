// The scene model shared by engine, oracle and generators (design: "Scene model").
//
// A building is a simple footprint polygon (counter-clockwise, may be non-convex) extruded from
// z = 0 to its height. For culling it is held as one or more convex vertical prisms (CVPs: the
// thesis's inner hull, ch. 3.1.1) whose union is the building, plus its bounding box (outer hull).
//
// A mesh object is a triangle mesh with an id: what a prism cannot express (a wall with a door
// or window through it, an arcade, a bridge over a street, an imported glTF/OBJ model). Model
// only what a scene requires: a scene of buildings alone is 2.5D and every engine method runs on
// it; a scene with mesh objects runs the oracle, frustum culling and outside subjects
// (engine/method.hpp: method_unavailable_reason says which and why).
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "core/geometry.hpp"

namespace cullcheck {

using ObjectId = std::uint32_t;

// A convex polygon (counter-clockwise, no repeated vertex) extruded from z = 0 to `height`.
struct ConvexVerticalPrism {
  std::vector<Vec2> ring;
  double height = 0.0;
};

struct Building {
  ObjectId id = 0;
  std::vector<Vec2> footprint;  // simple polygon, counter-clockwise, implicitly closed
  double height = 0.0;
  std::vector<ConvexVerticalPrism> prisms;  // convex decomposition of the footprint
  Box3 bounds;

  // Triangles of the rendered mesh: two per wall, a fan on the roof (no floor).
  std::size_t triangle_count() const { return 3 * footprint.size() - 2; }
};

// A closed or open triangle mesh, in scene-local metres. Triangles are counter-clockwise seen
// from outside where the mesh is closed; the oracle treats them as two-sided either way.
struct MeshObject {
  ObjectId id = 0;
  std::string name;  // as named in its source (glTF node or mesh, OBJ o/g group); may be empty
  std::vector<Vec3> vertices;
  std::vector<std::array<std::uint32_t, 3>> triangles;
  Box3 bounds;          // of the vertices the triangles use
  bool closed = false;  // every edge is shared by exactly two triangles (in opposite directions)
};

// Fills `bounds` and `closed` from the vertices and triangles.
void finish_mesh(MeshObject& m);

// Where a scene came from, so that a report or a failure names the command that rebuilds it.
struct Provenance {
  std::string generator = "file";
  std::uint64_t seed = 0;
  std::string parameters_json = "{}";  // the generator's parameters, as compact JSON
};

struct Scene {
  Provenance provenance;
  // World coordinates are local coordinates plus `origin`: far-from-origin (UTM-size) scenes are
  // rebased on load so that geometry keeps its precision (design: "Numerical extremes").
  Vec2 origin;
  std::vector<Building> buildings;  // buildings[i].id need not equal i; ids are unique
  std::vector<MeshObject> meshes;   // ids unique across buildings and meshes

  // 2.5D: every object is a building (a union of CVPs), so every engine method applies.
  bool prisms_only() const { return meshes.empty(); }
  std::size_t object_count() const { return buildings.size() + meshes.size(); }
  Box3 bounds() const;  // of buildings and meshes
  std::size_t triangle_count() const;
  const Building* find(ObjectId id) const;
  const MeshObject* find_mesh(ObjectId id) const;
  // Every object's id, sorted ascending.
  std::vector<ObjectId> ids() const;
};

// Fills `prisms` and `bounds` from `footprint` and `height` (footprint must already be valid and
// counter-clockwise). Convex footprints become one prism; others are partitioned.
void finish_building(Building& b);

// Polygon helpers used by validation and generators.
double signed_area(const std::vector<Vec2>& ring);
bool is_convex(const std::vector<Vec2>& ring);
bool is_simple(const std::vector<Vec2>& ring);

}  // namespace cullcheck
