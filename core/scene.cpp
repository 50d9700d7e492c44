#include "core/scene.hpp"

#include <algorithm>
#include <map>
#include <utility>

#include "core/convex_partition.hpp"

namespace cullcheck {

Box3 Scene::bounds() const {
  Box3 box;
  for (const Building& b : buildings) box.extend(b.bounds.lo), box.extend(b.bounds.hi);
  for (const MeshObject& m : meshes) box.extend(m.bounds.lo), box.extend(m.bounds.hi);
  return box;
}

std::size_t Scene::triangle_count() const {
  std::size_t n = 0;
  for (const Building& b : buildings) n += b.triangle_count();
  for (const MeshObject& m : meshes) n += m.triangles.size();
  return n;
}

const Building* Scene::find(ObjectId id) const {
  for (const Building& b : buildings)
    if (b.id == id) return &b;
  return nullptr;
}

const MeshObject* Scene::find_mesh(ObjectId id) const {
  for (const MeshObject& m : meshes)
    if (m.id == id) return &m;
  return nullptr;
}

std::vector<ObjectId> Scene::ids() const {
  std::vector<ObjectId> out;
  out.reserve(object_count());
  for (const Building& b : buildings) out.push_back(b.id);
  for (const MeshObject& m : meshes) out.push_back(m.id);
  std::sort(out.begin(), out.end());
  return out;
}

void finish_mesh(MeshObject& m) {
  m.bounds = Box3{};
  // Directed edge -> count; closed when each edge (a, b) is matched by exactly one (b, a).
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> edges;
  for (const auto& t : m.triangles) {
    for (int k = 0; k < 3; ++k) {
      m.bounds.extend(m.vertices[t[k]]);
      ++edges[{t[k], t[(k + 1) % 3]}];
    }
  }
  m.closed = !m.triangles.empty();
  for (const auto& [e, count] : edges) {
    const auto twin = edges.find({e.second, e.first});
    if (count != 1 || twin == edges.end() || twin->second != 1) {
      m.closed = false;
      break;
    }
  }
}

double signed_area(const std::vector<Vec2>& ring) {
  double twice = 0.0;
  for (std::size_t i = 0, n = ring.size(); i < n; ++i) twice += cross(ring[i], ring[(i + 1) % n]);
  return twice / 2;
}

bool is_convex(const std::vector<Vec2>& ring) {
  const std::size_t n = ring.size();
  if (n < 3) return false;
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2 a = ring[i], b = ring[(i + 1) % n], c = ring[(i + 2) % n];
    if (cross(b - a, c - b) < 0.0) return false;  // a right turn in a counter-clockwise ring
  }
  return true;
}

namespace {

int orientation(Vec2 a, Vec2 b, Vec2 c) {
  const double v = cross(b - a, c - a);
  return (v > 0) - (v < 0);
}

bool on_segment(Vec2 a, Vec2 b, Vec2 p) {
  return std::min(a.x, b.x) <= p.x && p.x <= std::max(a.x, b.x) && std::min(a.y, b.y) <= p.y &&
         p.y <= std::max(a.y, b.y);
}

bool segments_touch(Vec2 a, Vec2 b, Vec2 c, Vec2 d) {
  const int o1 = orientation(a, b, c), o2 = orientation(a, b, d);
  const int o3 = orientation(c, d, a), o4 = orientation(c, d, b);
  if (o1 != o2 && o3 != o4) return true;
  return (o1 == 0 && on_segment(a, b, c)) || (o2 == 0 && on_segment(a, b, d)) ||
         (o3 == 0 && on_segment(c, d, a)) || (o4 == 0 && on_segment(c, d, b));
}

}  // namespace

// O(n^2) pairwise edge test: footprints are small (validation caps them), and this is exact
// enough for rejecting self-intersections; touching non-adjacent edges count as not simple.
bool is_simple(const std::vector<Vec2>& ring) {
  const std::size_t n = ring.size();
  if (n < 3) return false;
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = i + 1; j < n; ++j) {
      const bool adjacent = j == i + 1 || (i == 0 && j == n - 1);
      const Vec2 a = ring[i], b = ring[(i + 1) % n], c = ring[j], d = ring[(j + 1) % n];
      if (adjacent) {
        // Adjacent edges share one vertex; they must not fold back onto each other.
        const Vec2 shared = (j == i + 1) ? b : a;
        const Vec2 p = (j == i + 1) ? a : b, q = (j == i + 1) ? d : c;
        if (orientation(p, shared, q) == 0 && dot(p - shared, q - shared) > 0) return false;
        continue;
      }
      if (segments_touch(a, b, c, d)) return false;
    }
  }
  return true;
}

void finish_building(Building& b) {
  b.prisms.clear();
  if (is_convex(b.footprint)) {
    b.prisms.push_back({b.footprint, b.height});
  } else {
    for (auto& ring : convex_partition(b.footprint)) b.prisms.push_back({std::move(ring), b.height});
  }
  b.bounds = Box3{};
  for (Vec2 p : b.footprint) b.bounds.extend(Vec3{p.x, p.y, 0.0}), b.bounds.extend(Vec3{p.x, p.y, b.height});
}

}  // namespace cullcheck
