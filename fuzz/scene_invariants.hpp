// The invariants of an accepted scene that the engine, the oracle and the writers rely on without
// checking again (core/scene.hpp, core/scene_io.hpp): a reader that lets one through has handed
// later code an out-of-range index or a NaN, so the harness treats it as a crash.
#pragma once

#include <cmath>
#include <set>
#include <string>

#include "core/scene.hpp"
#include "core/scene_io.hpp"
#include "fuzz/harness.hpp"

namespace cullcheck::fuzz {

inline bool finite(Vec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

inline void check_scene(const Scene& scene) {
  require(std::isfinite(scene.origin.x) && std::isfinite(scene.origin.y), "origin is finite");
  std::set<ObjectId> ids;
  for (const Building& b : scene.buildings) {
    const std::string name = "building " + std::to_string(b.id);
    require(ids.insert(b.id).second, name + ": id is unique");
    require(b.footprint.size() >= 3 && b.footprint.size() <= kMaxFootprintVertices, name + ": footprint size");
    require(std::isfinite(b.height) && b.height > 0.0 && b.height <= kMaxHeight, name + ": height");
    for (Vec2 p : b.footprint) require(std::isfinite(p.x) && std::isfinite(p.y), name + ": footprint is finite");
    require(signed_area(b.footprint) > 0.0, name + ": footprint is counter-clockwise");
    require(!b.prisms.empty(), name + ": has prisms");
    for (const ConvexVerticalPrism& prism : b.prisms) require(prism.ring.size() >= 3, name + ": prism ring size");
    require(finite(b.bounds.lo) && finite(b.bounds.hi), name + ": bounds are finite");
  }
  for (const MeshObject& m : scene.meshes) {
    const std::string name = "mesh " + std::to_string(m.id);
    require(ids.insert(m.id).second, name + ": id is unique across buildings and meshes");
    require(!m.triangles.empty(), name + ": has triangles");
    require(m.vertices.size() <= kMaxMeshVertices, name + ": vertex count within the limit");
    for (const Vec3& v : m.vertices) require(finite(v), name + ": vertices are finite");
    for (const auto& t : m.triangles)
      for (std::uint32_t k : t) require(k < m.vertices.size(), name + ": triangle index in range");
    require(finite(m.bounds.lo) && finite(m.bounds.hi), name + ": bounds are finite");
  }
}

}  // namespace cullcheck::fuzz
