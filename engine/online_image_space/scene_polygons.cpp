#include "engine/online_image_space/scene_polygons.hpp"

namespace cullcheck::online {
namespace {

void push(ScenePolygons& out, std::uint32_t object, std::initializer_list<Vec3> ring) {
  Box3 box;
  for (const Vec3& v : ring) out.vertices.push_back(v), box.extend(v);
  out.first.push_back(static_cast<std::uint32_t>(out.vertices.size()));
  out.object.push_back(object);
  out.box.push_back(box);
}

}  // namespace

void append_building(const Building& b, std::uint32_t object, ScenePolygons& out) {
  if (out.first.empty()) out.first.push_back(0);
  const auto& f = b.footprint;
  for (std::size_t i = 0; i < f.size(); ++i) {
    const Vec2 a = f[i], c = f[(i + 1) % f.size()];
    if (a == c) continue;
    push(out, object, {{a.x, a.y, 0.0}, {c.x, c.y, 0.0}, {c.x, c.y, b.height}, {a.x, a.y, b.height}});
  }
  for (const ConvexVerticalPrism& prism : b.prisms) {
    Box3 box;
    for (const Vec2& v : prism.ring) out.vertices.push_back({v.x, v.y, prism.height}), box.extend(out.vertices.back());
    out.first.push_back(static_cast<std::uint32_t>(out.vertices.size()));
    out.object.push_back(object);
    out.box.push_back(box);
  }
}

void append_mesh(const MeshObject& m, std::uint32_t object, ScenePolygons& out) {
  if (out.first.empty()) out.first.push_back(0);
  for (const auto& t : m.triangles) {
    const Vec3 a = m.vertices[t[0]], b = m.vertices[t[1]], c = m.vertices[t[2]];
    const Vec3 n = cross(b - a, c - a);
    if (dot(n, n) == 0.0) continue;  // covers nothing
    push(out, object, {a, b, c});
  }
}

ScenePolygons scene_polygons(const Scene& scene) {
  ScenePolygons out;
  out.first.push_back(0);
  for (const Building& b : scene.buildings) {
    append_building(b, static_cast<std::uint32_t>(out.ids.size()), out);
    out.ids.push_back(b.id);
  }
  for (const MeshObject& m : scene.meshes) {
    append_mesh(m, static_cast<std::uint32_t>(out.ids.size()), out);
    out.ids.push_back(m.id);
  }
  return out;
}

}  // namespace cullcheck::online
