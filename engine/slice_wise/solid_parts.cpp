#include "engine/slice_wise/solid_parts.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <set>
#include <tuple>

namespace cullcheck::slice_wise {
namespace {

constexpr double kPlaneTolerance = 1e-7;  // metres: a vertex this close to a plane lies in it
constexpr double kLeftShare = 1e-12;      // of a triangle's area: less left uncovered counts as covered
constexpr std::size_t kMaxSolidPieces = 256;   // beyond this, a triangle is kept as boundary

using Polygon = std::vector<Vec2>;

double area2(const Polygon& p) {
  double s = 0;
  for (std::size_t i = 0; i < p.size(); ++i) s += cross(p[i], p[(i + 1) % p.size()]);
  return s;
}

// The part of convex `in` on the left of a -> b (keep_left) or on its right.
Polygon half_plane(const Polygon& in, Vec2 a, Vec2 b, bool keep_left) {
  Polygon out;
  const Vec2 e = b - a;
  auto side = [&](Vec2 q) { return keep_left ? cross(e, q - a) : -cross(e, q - a); };
  for (std::size_t i = 0; i < in.size(); ++i) {
    const Vec2 p = in[i], q = in[(i + 1) % in.size()];
    const double sp = side(p), sq = side(q);
    if (sp >= 0) out.push_back(p);
    if ((sp > 0 && sq < 0) || (sp < 0 && sq > 0)) out.push_back(p + (q - p) * (sp / (sp - sq)));
  }
  return out.size() >= 3 ? out : Polygon{};
}

// Convex `piece` minus the counter-clockwise triangle `t`, as convex pieces.
void subtract(const Polygon& piece, const Vec2 t[3], std::vector<Polygon>& out) {
  Polygon inside = piece;
  for (int i = 0; i < 3 && !inside.empty(); ++i) {
    Polygon outside = half_plane(inside, t[i], t[(i + 1) % 3], false);
    if (!outside.empty() && area2(outside) > 0) out.push_back(std::move(outside));
    inside = half_plane(inside, t[i], t[(i + 1) % 3], true);
  }
}

// Plane key: the unit normal and offset, rounded (a pair rounding apart is only missed).
using PlaneKey = std::tuple<long, long, long, long>;
PlaneKey key_of(Vec3 n, double d) {
  return {std::lround(n.x * 1e6), std::lround(n.y * 1e6), std::lround(n.z * 1e6), std::lround(d * 1e3)};
}

// Coordinates in a plane of normal n: the two axes left when its dominant axis is dropped.
struct PlaneProjection {
  int drop;
  explicit PlaneProjection(Vec3 n)
      : drop(std::abs(n.x) >= std::abs(n.y) && std::abs(n.x) >= std::abs(n.z) ? 0 : std::abs(n.y) >= std::abs(n.z) ? 1 : 2) {}
  Vec2 operator()(Vec3 v) const { return drop == 0 ? Vec2{v.y, v.z} : drop == 1 ? Vec2{v.z, v.x} : Vec2{v.x, v.y}; }
  // Triangle t of m, counter-clockwise.
  Polygon triangle(const MeshObject& m, std::uint32_t t) const {
    const auto& tri = m.triangles[t];
    Polygon p{(*this)(m.vertices[tri[0]]), (*this)(m.vertices[tri[1]]), (*this)(m.vertices[tri[2]])};
    if (area2(p) < 0) std::swap(p[1], p[2]);
    return p;
  }
};

// The plane of triangle t of m as a unit normal (by the winding) and offset; false when degenerate.
bool plane_of(const MeshObject& m, std::uint32_t t, Vec3& normal, double& offset) {
  const auto& tri = m.triangles[t];
  const Vec3 c = cross(m.vertices[tri[1]] - m.vertices[tri[0]], m.vertices[tri[2]] - m.vertices[tri[0]]);
  const double len = length(c);
  if (!(len > 0)) return false;
  normal = c * (1.0 / len), offset = dot(normal, m.vertices[tri[0]]);
  return true;
}

// Whether every vertex of triangle t of m lies within the tolerance of the plane n . p = offset.
bool in_plane(const MeshObject& m, std::uint32_t t, Vec3 n, double offset) {
  for (std::uint32_t v : m.triangles[t])
    if (std::abs(dot(n, m.vertices[v]) - offset) > kPlaneTolerance) return false;
  return true;
}

}  // namespace

SolidParts solid_parts(const MeshObject& m) {
  SolidParts out;
  const std::size_t nt = m.triangles.size();
  out.part_of.assign(nt, 0);
  out.cover.assign(nt, SolidParts::boundary);
  // Solids: triangles joined through shared vertices (a solid's own vertices are welded, two
  // solids' are not).
  std::vector<std::uint32_t> root(m.vertices.size());
  std::iota(root.begin(), root.end(), 0u);
  auto find = [&](std::uint32_t v) {
    while (root[v] != v) v = root[v] = root[root[v]];
    return v;
  };
  for (const auto& t : m.triangles)
    for (int k = 1; k < 3; ++k) root[find(t[k])] = find(t[0]);
  std::map<std::uint32_t, std::uint32_t> number;
  for (std::size_t i = 0; i < nt; ++i) {
    const auto [at, fresh] = number.emplace(find(m.triangles[i][0]), static_cast<std::uint32_t>(number.size()));
    out.part_of[i] = at->second;
  }
  out.parts = static_cast<std::uint32_t>(number.size());
  if (out.parts < 2) return out;

  std::vector<Vec3> normal(nt);
  std::vector<double> offset(nt);
  std::map<PlaneKey, std::vector<std::uint32_t>> by_plane;
  for (std::uint32_t i = 0; i < nt; ++i) {
    if (!plane_of(m, i, normal[i], offset[i])) continue;  // degenerate: no side to be inside on
    by_plane[key_of(normal[i], offset[i])].push_back(i);
  }
  for (std::uint32_t i = 0; i < nt; ++i) {
    if (normal[i] == Vec3{}) continue;
    const auto against = by_plane.find(key_of(normal[i] * -1.0, -offset[i]));
    if (against == by_plane.end()) continue;
    // Project on the plane's dominant axis, so that t is counter-clockwise.
    const Vec3 n = normal[i];
    const PlaneProjection project(n);
    auto lift = [&](Vec2 q) {  // back onto the plane n . p = offset
      const double d = offset[i];
      if (project.drop == 0) return Vec3{(d - n.y * q.x - n.z * q.y) / n.x, q.x, q.y};
      if (project.drop == 1) return Vec3{q.y, (d - n.z * q.x - n.x * q.y) / n.y, q.x};
      return Vec3{q.x, q.y, (d - n.x * q.x - n.y * q.y) / n.z};
    };
    const Polygon own = project.triangle(m, i);
    const double total = area2(own);
    std::vector<Polygon> left{own}, next;
    bool touched = false;
    for (std::uint32_t j : against->second) {
      if (out.part_of[j] == out.part_of[i]) continue;
      if (!in_plane(m, j, n, offset[i])) continue;
      const Polygon covering = project.triangle(m, j);
      const Vec2 cover[3] = {covering[0], covering[1], covering[2]};
      next.clear();
      touched = true;
      for (const Polygon& piece : left) subtract(piece, cover, next);
      left.swap(next);
      if (left.empty() || left.size() > kMaxSolidPieces) break;
    }
    if (!touched || left.size() > kMaxSolidPieces) continue;
    double remaining = 0;
    for (const Polygon& piece : left) remaining += area2(piece);
    if (remaining <= kLeftShare * total) {
      out.cover[i] = SolidParts::interior, ++out.interior_count;
    } else if (remaining < (1 - kLeftShare) * total) {
      out.cover[i] = SolidParts::partly, ++out.partly_count;
      auto& pieces = out.boundary_pieces[i];
      for (const Polygon& piece : left) {
        pieces.emplace_back();
        for (Vec2 q : piece) pieces.back().push_back(lift(q));
      }
    }
  }
  return out;
}

std::vector<std::pair<std::uint32_t, std::uint32_t>> touching_pairs(const std::vector<const MeshObject*>& meshes) {
  const auto n = static_cast<std::uint32_t>(meshes.size());
  // Pairs whose boxes meet (within the plane tolerance): a sweep along x.
  std::vector<std::uint32_t> by_x(n);
  std::iota(by_x.begin(), by_x.end(), 0u);
  std::sort(by_x.begin(), by_x.end(), [&](std::uint32_t a, std::uint32_t b) { return meshes[a]->bounds.lo.x < meshes[b]->bounds.lo.x; });
  std::set<std::pair<std::uint32_t, std::uint32_t>> near;
  for (std::size_t p = 0; p < n; ++p) {
    const Box3& a = meshes[by_x[p]]->bounds;
    for (std::size_t q = p + 1; q < n && meshes[by_x[q]]->bounds.lo.x <= a.hi.x + kPlaneTolerance; ++q) {
      const Box3& b = meshes[by_x[q]]->bounds;
      if (b.lo.y > a.hi.y + kPlaneTolerance || a.lo.y > b.hi.y + kPlaneTolerance || b.lo.z > a.hi.z + kPlaneTolerance ||
          a.lo.z > b.hi.z + kPlaneTolerance)
        continue;
      near.insert(std::minmax(by_x[p], by_x[q]));
    }
  }
  if (near.empty()) return {};
  // The triangles of the meshes in some such pair, by plane.
  struct Face {
    PlaneKey key;
    std::uint32_t mesh, triangle;
    Vec3 normal;
    double offset;
  };
  std::vector<std::uint8_t> wanted(n, 0);
  for (const auto& [a, b] : near) wanted[a] = wanted[b] = 1;
  std::vector<Face> faces;
  for (std::uint32_t i = 0; i < n; ++i) {
    if (!wanted[i]) continue;
    const MeshObject& m = *meshes[i];
    for (std::uint32_t t = 0; t < m.triangles.size(); ++t) {
      Vec3 normal;
      double offset;
      if (!plane_of(m, t, normal, offset)) continue;
      faces.push_back({key_of(normal, offset), i, t, normal, offset});
    }
  }
  auto by_key = [](const Face& a, const Face& b) { return std::tie(a.key, a.mesh, a.triangle) < std::tie(b.key, b.mesh, b.triangle); };
  std::sort(faces.begin(), faces.end(), by_key);
  std::set<std::pair<std::uint32_t, std::uint32_t>> found;
  for (const Face& f : faces) {
    Face against{key_of(f.normal * -1.0, -f.offset), 0, 0, {}, 0};
    auto it = std::lower_bound(faces.begin(), faces.end(), against, by_key);
    const Vec3 n = f.normal;
    const PlaneProjection project(n);
    const Polygon own = project.triangle(*meshes[f.mesh], f.triangle);
    for (; it != faces.end() && it->key == against.key; ++it) {
      if (it->mesh <= f.mesh) continue;  // each pair once, from its lower mesh
      const auto pair = std::make_pair(f.mesh, it->mesh);
      if (found.count(pair) || !near.count(pair)) continue;
      const MeshObject& o = *meshes[it->mesh];
      if (!in_plane(o, it->triangle, n, f.offset)) continue;
      const Polygon other = project.triangle(o, it->triangle);
      Polygon common = own;
      for (int k = 0; k < 3 && !common.empty(); ++k) common = half_plane(common, other[k], other[(k + 1) % 3], true);
      if (!common.empty() && area2(common) > 1e-6 * std::min(area2(own), area2(other))) found.insert(pair);
    }
  }
  return {found.begin(), found.end()};
}

}  // namespace cullcheck::slice_wise
