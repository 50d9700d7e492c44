#include "oracle/mesh.hpp"

#include <cmath>
#include <map>
#include <stdexcept>
#include <string>
#include <tuple>
#include <utility>

#include "core/errors.hpp"
#include "oracle/roof_triangulation.hpp"

namespace cullcheck::oracle {

void check_merged_triangle_count(std::size_t triangles) {
  if (triangles > kMaxMergedTriangles)
    throw InputError("scene", "triangles",
                     "has " + std::to_string(triangles) + " triangles; the ray oracle's one Embree mesh holds at most " +
                         std::to_string(kMaxMergedTriangles) + " (three unshared 32-bit vertex indices each)");
}

TriangleMesh triangulate(const Scene& scene) {
  check_merged_triangle_count(scene.triangle_count());
  TriangleMesh mesh;
  if (scene.object_count() > 0) {
    const Box3 box = scene.bounds();
    mesh.origin = {std::round((box.lo.x + box.hi.x) / 2), std::round((box.lo.y + box.hi.y) / 2), 0.0};
  }
  mesh.building_count = scene.buildings.size();
  for (const Building& b : scene.buildings) mesh.object_ids.push_back(b.id);
  for (const MeshObject& m : scene.meshes) mesh.object_ids.push_back(m.id);
  mesh.vertices.reserve(3 * scene.triangle_count());
  mesh.triangles.reserve(scene.triangle_count());
  auto add_triangle = [&](Vec3 a, Vec3 b, Vec3 c, std::uint32_t owner) {
    const auto base = static_cast<std::uint32_t>(mesh.vertices.size());
    mesh.vertices.push_back(a), mesh.vertices.push_back(b), mesh.vertices.push_back(c);
    mesh.triangles.push_back({base, base + 1, base + 2});
    mesh.owner_index.push_back(owner);
    mesh.owner_id.push_back(mesh.object_ids[owner]);
  };
  // Vertices are not shared between triangles: Embree's watertight (robust) test needs equal
  // positions, not equal indices, and the same double always rounds to the same float.
  for (std::uint32_t i = 0; i < scene.buildings.size(); ++i) {
    const Building& b = scene.buildings[i];
    mesh.first_triangle.push_back(static_cast<std::uint32_t>(mesh.triangles.size()));
    const std::size_t n = b.footprint.size();
    for (std::size_t k = 0; k < n; ++k) {
      const Vec2 p = b.footprint[k], q = b.footprint[(k + 1) % n];
      const Vec3 p0{p.x, p.y, 0.0}, q0{q.x, q.y, 0.0}, p1{p.x, p.y, b.height}, q1{q.x, q.y, b.height};
      // Counter-clockwise footprint: (p0, q0, q1) has the outward normal.
      add_triangle(p0, q0, q1, i);
      add_triangle(p0, q1, p1, i);
    }
    try {
      mesh.roofs.push_back(triangulate_roof(b.footprint));
    } catch (const std::invalid_argument& e) {
      throw InputError("building " + std::to_string(b.id), "footprint", e.what());
    }
    for (const auto& t : mesh.roofs.back()) {
      const Vec2 p = b.footprint[t[0]], q = b.footprint[t[1]], r = b.footprint[t[2]];
      add_triangle({p.x, p.y, b.height}, {q.x, q.y, b.height}, {r.x, r.y, b.height}, i);
    }
  }
  for (std::size_t k = 0; k < scene.meshes.size(); ++k) {
    const MeshObject& m = scene.meshes[k];
    const auto owner = static_cast<std::uint32_t>(scene.buildings.size() + k);
    mesh.first_triangle.push_back(static_cast<std::uint32_t>(mesh.triangles.size()));
    for (const auto& t : m.triangles) add_triangle(m.vertices[t[0]], m.vertices[t[1]], m.vertices[t[2]], owner);
    mesh.mesh_edges.push_back(mesh_edges_of(m));
  }
  return mesh;
}

std::vector<MeshEdge> mesh_edges_of(const MeshObject& m) {
  using Point = std::tuple<double, double, double>;
  auto point = [&](std::uint32_t v) { return Point{m.vertices[v].x, m.vertices[v].y, m.vertices[v].z}; };
  std::map<std::pair<Point, Point>, std::size_t> index;  // by end points, lower first
  std::vector<MeshEdge> edges;
  for (std::uint32_t t = 0; t < m.triangles.size(); ++t)
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t u = m.triangles[t][k], w = m.triangles[t][(k + 1) % 3];
      const Point pu = point(u), pw = point(w);
      if (pu == pw) continue;  // a degenerate triangle's collapsed edge
      const auto key = pu < pw ? std::pair{pu, pw} : std::pair{pw, pu};
      const auto [it, added] = index.emplace(key, edges.size());
      if (added) edges.push_back(MeshEdge{m.vertices[u], m.vertices[w], {}});
      edges[it->second].triangles.push_back(t);
    }
  return edges;
}

}  // namespace cullcheck::oracle
