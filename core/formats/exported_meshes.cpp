// The triangles every object is exported as (mesh_formats.hpp: exported_meshes).
#include <map>

#include "core/formats/exported_object.hpp"
#include "core/formats/mesh_formats.hpp"

namespace cullcheck::formats {

MeshObject detail::building_surface(const Building& b) {
  MeshObject m;
  m.id = b.id;
  m.name = building_name(b.id);
  const std::size_t n = b.footprint.size();
  m.vertices.reserve(2 * n);
  std::map<std::pair<double, double>, std::uint32_t> top_of;  // footprint vertex -> its top vertex
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2 p = b.footprint[i];
    m.vertices.push_back({p.x, p.y, 0.0});
    m.vertices.push_back({p.x, p.y, b.height});
    top_of.emplace(std::pair{p.x, p.y}, static_cast<std::uint32_t>(2 * i + 1));
  }
  m.triangles.reserve(3 * n);
  // Walls, counter-clockwise seen from outside (the footprint is counter-clockwise from above).
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t j = (i + 1) % n;
    const auto bi = static_cast<std::uint32_t>(2 * i), ti = bi + 1;
    const auto bj = static_cast<std::uint32_t>(2 * j), tj = bj + 1;
    m.triangles.push_back({bi, bj, tj});
    m.triangles.push_back({bi, tj, ti});
  }
  // Roof: a fan over each CVP. The partition reuses footprint vertices (core/convex_partition),
  // so every prism vertex is a top vertex already; one that is not gets its own (defensive).
  auto top = [&](Vec2 p) {
    auto it = top_of.find({p.x, p.y});
    if (it != top_of.end()) return it->second;
    m.vertices.push_back({p.x, p.y, b.height});
    const auto index = static_cast<std::uint32_t>(m.vertices.size() - 1);
    top_of.emplace(std::pair{p.x, p.y}, index);
    return index;
  };
  for (const ConvexVerticalPrism& prism : b.prisms) {
    const std::vector<Vec2>& r = prism.ring;
    for (std::size_t k = 1; k + 1 < r.size(); ++k) {
      if (cross(r[k] - r[0], r[k + 1] - r[0]) == 0.0) continue;  // collinear ring vertices
      m.triangles.push_back({top(r[0]), top(r[k]), top(r[k + 1])});
    }
  }
  return m;
}

MeshObject exported_mesh(const Building& b) {
  MeshObject m = detail::building_surface(b);
  finish_mesh(m);
  return m;
}

std::vector<MeshObject> exported_meshes(const Scene& scene) {
  std::vector<MeshObject> out;
  out.reserve(scene.object_count());
  for (const Building& b : scene.buildings) out.push_back(exported_mesh(b));
  for (const MeshObject& m : scene.meshes) out.push_back(m);
  return out;
}

}  // namespace cullcheck::formats
