// The scene as one triangle mesh, the form the ray oracle hands to Embree.
//
// Each building contributes its walls (two triangles per footprint edge, z = 0 to height) and its
// roof (each convex vertical prism's ring fanned from its first vertex: the prisms partition the
// footprint with diagonals only, so the roof has exactly footprint.size() - 2 triangles). No
// floor: nothing is seen from below the ground plane. Triangle i belongs to building
// owner_index[i] (index into Scene::buildings), whose stable id is owner_id[i].
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "core/geometry.hpp"
#include "core/scene.hpp"

namespace cullcheck::oracle {

struct TriangleMesh {
  // Vertices in scene-local metres (double). Embree receives them as floats relative to
  // `origin`, a whole-metre point near the scene's centre, so single precision is spent on the
  // scene's extent rather than on its distance from (0, 0).
  Vec3 origin;
  std::vector<Vec3> vertices;
  std::vector<std::array<std::uint32_t, 3>> triangles;
  std::vector<std::uint32_t> owner_index;  // primID -> index into Scene::buildings
  std::vector<ObjectId> owner_id;          // primID -> Building::id
};

TriangleMesh triangulate(const Scene& scene);

}  // namespace cullcheck::oracle
