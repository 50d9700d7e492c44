#include "oracle/witness_cover.hpp"

#include <algorithm>
#include <cmath>

namespace cullcheck::oracle {

bool turned_away_from(const TriangleMesh& mesh, std::uint32_t triangle, Vec3 direction) {
  const auto& tri = mesh.triangles[triangle];
  const Vec3 a = mesh.vertices[tri[0]];
  const Vec3 n = cross(mesh.vertices[tri[1]] - a, mesh.vertices[tri[2]] - a);
  const double len = length(n);
  return len > 0 && dot(n, direction) > 1e-9 * len * length(direction);
}

double point_triangle_distance(Vec3 p, Vec3 a, Vec3 b, Vec3 c) {
  // Closest point by Voronoi regions of the triangle (Ericson, Real-Time Collision Detection 5.1.5).
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = dot(ab, ap), d2 = dot(ac, ap);
  if (d1 <= 0 && d2 <= 0) return length(p - a);
  const Vec3 bp = p - b;
  const double d3 = dot(ab, bp), d4 = dot(ac, bp);
  if (d3 >= 0 && d4 <= d3) return length(p - b);
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return length(p - (a + ab * (d1 / (d1 - d3))));
  const Vec3 cp = p - c;
  const double d5 = dot(ab, cp), d6 = dot(ac, cp);
  if (d6 >= 0 && d5 <= d6) return length(p - c);
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return length(p - (a + ac * (d2 / (d2 - d6))));
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) return length(p - (b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)))));
  const double denom = va + vb + vc;
  if (!(denom > 0)) return std::min({length(p - a), length(p - b), length(p - c)});  // degenerate
  const double v = vb / denom, w = vc / denom;
  return length(p - (a + ab * v + ac * w));
}

bool seen_point_drawn(const TriangleMesh& mesh, std::uint32_t object_index, const WitnessRay& ray,
                      const std::function<bool(std::uint32_t local)>& drawn, double tolerance_m) {
  if (object_index >= mesh.first_triangle.size()) return false;
  const std::uint32_t first = mesh.first_triangle[object_index];
  const std::uint32_t end = object_index + 1 < mesh.first_triangle.size() ? mesh.first_triangle[object_index + 1]
                                                                          : static_cast<std::uint32_t>(mesh.triangles.size());
  for (std::uint32_t t = first; t < end; ++t) {
    if (turned_away_from(mesh, t, ray.direction)) continue;  // not drawn with back faces culled
    const auto& tri = mesh.triangles[t];
    const Vec3 a = mesh.vertices[tri[0]], b = mesh.vertices[tri[1]], c = mesh.vertices[tri[2]];
    if (point_triangle_distance(ray.hit_point, a, b, c) > tolerance_m) continue;
    if (drawn(t - first)) return true;
  }
  return false;
}

WitnessVerdict witness_verdict(const TriangleMesh& mesh, std::uint32_t prim, const WitnessRay& ray, const std::vector<char>* kept) {
  if (!kept) return WitnessVerdict::missed;
  const std::uint32_t owner = mesh.owner_index[prim];
  if (owner < mesh.building_count || (*kept)[prim - mesh.first_triangle[owner]]) return WitnessVerdict::drawn;
  return seen_point_drawn(mesh, owner, ray, [&](std::uint32_t local) { return (*kept)[local] != 0; })
             ? WitnessVerdict::drawn_by_another
             : WitnessVerdict::missed;
}

}  // namespace cullcheck::oracle
