// Prism detection (mesh_formats.hpp: as_vertical_prism).
//
// Why each check is needed for soundness (a "yes" must mean the mesh bounds the returned prism):
//  - two height levels: a vertex anywhere else (a pyramid's apex, a box lifted off the ground)
//    is not on a prism's surface;
//  - the roof (triangles at the top level) has one boundary loop and covers its area once: a
//    second loop is a hole or a second roof, an edge used twice the same way is a fold, and
//    overlapping triangles show as more roof area than the outline holds;
//  - every other triangle lies on one outline edge's vertical rectangle, whose triangles cover it
//    once with no boundary inside it (a gap's rim would be such a boundary) and sum to its area;
//  - a floor, if present, has the roof's outline.
#include <algorithm>
#include <cmath>
#include <map>
#include <tuple>

#include "core/errors.hpp"
#include "core/formats/mesh_formats.hpp"
#include "core/scene_io.hpp"

namespace cullcheck::formats {
namespace {

using Edge = std::pair<std::uint32_t, std::uint32_t>;
using Triangle = std::array<std::uint32_t, 3>;

// Directed edges of consistently oriented triangles; nullopt when an edge is used twice in the
// same direction (overlap or fold).
std::optional<std::map<Edge, int>> directed_edges(const std::vector<Triangle>& triangles) {
  std::map<Edge, int> edges;
  for (const Triangle& t : triangles)
    for (int k = 0; k < 3; ++k)
      if (++edges[{t[k], t[(k + 1) % 3]}] > 1) return std::nullopt;
  return edges;
}

std::vector<Edge> boundary_of(const std::map<Edge, int>& edges) {
  std::vector<Edge> out;
  for (const auto& [e, count] : edges)
    if (!edges.contains({e.second, e.first})) out.push_back(e);
  return out;
}

// The one closed loop the boundary edges form (vertex indices in order), or nullopt when they
// form several loops or a vertex has two outgoing edges (a pinch).
std::optional<std::vector<std::uint32_t>> single_loop(const std::vector<Edge>& boundary) {
  if (boundary.size() < 3) return std::nullopt;
  std::map<std::uint32_t, std::uint32_t> next;
  for (const Edge& e : boundary)
    if (!next.emplace(e.first, e.second).second) return std::nullopt;
  std::vector<std::uint32_t> loop;
  std::uint32_t v = boundary.front().first;
  do {
    loop.push_back(v);
    auto it = next.find(v);
    if (it == next.end() || loop.size() > boundary.size()) return std::nullopt;
    v = it->second;
  } while (v != boundary.front().first);
  if (loop.size() != boundary.size()) return std::nullopt;
  return loop;
}

// Drops vertices lying within `tol` of the straight line between their neighbours (and between
// them, so a spike is kept), until none is left.
std::vector<Vec2> merge_collinear(std::vector<Vec2> ring, double tol) {
  bool changed = true;
  while (changed && ring.size() > 3) {
    changed = false;
    for (std::size_t i = 0; i < ring.size() && ring.size() > 3; ++i) {
      const Vec2 a = ring[(i + ring.size() - 1) % ring.size()], b = ring[i], c = ring[(i + 1) % ring.size()];
      if (dot(b - a, c - b) > 0.0 && distance_to_segment(b, a, c) <= tol) {
        ring.erase(ring.begin() + static_cast<std::ptrdiff_t>(i));
        changed = true;
        --i;
      }
    }
  }
  return ring;
}

double perimeter(const std::vector<Vec2>& ring) {
  double p = 0.0;
  for (std::size_t i = 0; i < ring.size(); ++i) p += length(ring[(i + 1) % ring.size()] - ring[i]);
  return p;
}

// The outline of horizontal triangles (plan view, oriented counter-clockwise here whatever their
// winding), when they cover one simple polygon exactly once; nullopt otherwise.
std::optional<std::vector<Vec2>> horizontal_outline(std::vector<Triangle> triangles, const std::vector<Vec2>& plan,
                                                    double tol) {
  double area = 0.0;
  for (Triangle& t : triangles) {
    const double a = cross(plan[t[1]] - plan[t[0]], plan[t[2]] - plan[t[0]]) / 2;
    if (!(std::abs(a) > 0.0)) return std::nullopt;  // a vertical sliver at one level
    if (a < 0) std::swap(t[1], t[2]);
    area += std::abs(a);
  }
  const auto edges = directed_edges(triangles);
  if (!edges) return std::nullopt;
  const auto loop = single_loop(boundary_of(*edges));
  if (!loop) return std::nullopt;
  std::vector<Vec2> ring;
  for (std::uint32_t v : *loop) ring.push_back(plan[v]);
  ring = merge_collinear(std::move(ring), tol);
  if (ring.size() < 3 || ring.size() > kMaxFootprintVertices || !is_simple(ring)) return std::nullopt;
  const double outline_area = signed_area(ring);
  if (!(outline_area > 0.0) || std::abs(outline_area - area) > tol * perimeter(ring)) return std::nullopt;
  return ring;
}

bool same_ring(const std::vector<Vec2>& a, const std::vector<Vec2>& b, double tol) {
  if (a.size() != b.size()) return false;
  for (std::size_t shift = 0; shift < a.size(); ++shift) {
    bool all = true;
    for (std::size_t i = 0; i < a.size() && all; ++i) all = length(a[i] - b[(i + shift) % b.size()]) <= tol;
    if (all) return true;
  }
  return false;
}

struct WallTriangle {
  std::array<std::uint32_t, 3> v;
  std::array<double, 3> s;  // position along the outline edge
};

// The wall triangles on one outline edge cover its rectangle [0, length] x [0, height] exactly:
// their area sums to the rectangle's and their boundary lies on the rectangle's border.
bool covers_rectangle(std::vector<WallTriangle> walls, const std::vector<Vec3>& vertices, double edge_length,
                      double height, double tol) {
  double area = 0.0;
  std::vector<Triangle> oriented;
  std::map<std::uint32_t, std::pair<double, double>> sz;  // vertex -> (s, z)
  for (WallTriangle& w : walls) {
    std::array<std::pair<double, double>, 3> p;
    for (int k = 0; k < 3; ++k) p[k] = {w.s[k], vertices[w.v[k]].z};
    const double a = ((p[1].first - p[0].first) * (p[2].second - p[0].second) -
                      (p[2].first - p[0].first) * (p[1].second - p[0].second)) / 2;
    if (!(std::abs(a) > 0.0)) return false;
    Triangle t = w.v;
    if (a < 0) std::swap(t[1], t[2]);
    oriented.push_back(t);
    area += std::abs(a);
    for (int k = 0; k < 3; ++k) sz[w.v[k]] = p[k];
  }
  if (std::abs(area - edge_length * height) > tol * 2 * (edge_length + height)) return false;
  const auto edges = directed_edges(oriented);
  if (!edges) return false;
  auto side = [&](std::pair<double, double> q) {
    int bits = 0;
    if (std::abs(q.first) <= tol) bits |= 1;
    if (std::abs(q.first - edge_length) <= tol) bits |= 2;
    if (std::abs(q.second) <= tol) bits |= 4;
    if (std::abs(q.second - height) <= tol) bits |= 8;
    return bits;
  };
  for (const Edge& e : boundary_of(*edges))
    if ((side(sz[e.first]) & side(sz[e.second])) == 0) return false;  // not on one border side
  return true;
}

}  // namespace

std::optional<Building> as_vertical_prism(const MeshObject& mesh) {
  if (mesh.triangles.empty()) return std::nullopt;
  // Weld by exact position, so that a triangle soup has the topology of the surface it makes.
  std::map<std::tuple<double, double, double>, std::uint32_t> weld_of;
  std::vector<Vec3> vertices;
  std::vector<Triangle> triangles;
  double scale = 1.0;
  for (const auto& t : mesh.triangles) {
    Triangle w{};
    for (int k = 0; k < 3; ++k) {
      if (t[k] >= mesh.vertices.size()) return std::nullopt;
      const Vec3 v = mesh.vertices[t[k]];
      if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z)) return std::nullopt;
      auto [it, added] = weld_of.emplace(std::tuple{v.x, v.y, v.z}, static_cast<std::uint32_t>(vertices.size()));
      if (added) vertices.push_back(v);
      w[k] = it->second;
      scale = std::max({scale, std::abs(v.x), std::abs(v.y), std::abs(v.z)});
    }
    if (w[0] == w[1] || w[1] == w[2] || w[0] == w[2]) continue;  // zero area: bounds nothing
    triangles.push_back(w);
  }
  if (triangles.empty()) return std::nullopt;
  const double tol = kPrismTolerance * scale;

  // Two levels: the ground and one height h.
  double h = 0.0;
  for (const Vec3& v : vertices) h = std::max(h, v.z);
  if (!(h > tol)) return std::nullopt;
  enum Level : std::uint8_t { ground, top };
  std::vector<Level> level(vertices.size());
  std::vector<Vec2> plan(vertices.size());
  for (std::size_t i = 0; i < vertices.size(); ++i) {
    if (std::abs(vertices[i].z) <= tol) level[i] = ground;
    else if (std::abs(vertices[i].z - h) <= tol) level[i] = top;
    else return std::nullopt;
    plan[i] = {vertices[i].x, vertices[i].y};
  }

  std::vector<Triangle> roof, floor, sides;
  for (const Triangle& t : triangles) {
    const int tops = (level[t[0]] == top) + (level[t[1]] == top) + (level[t[2]] == top);
    (tops == 3 ? roof : tops == 0 ? floor : sides).push_back(t);
  }
  if (roof.empty() || sides.empty()) return std::nullopt;
  const std::size_t wall_limit = 64 * kMaxFootprintVertices;
  if (sides.size() > wall_limit) return std::nullopt;
  const auto outline = horizontal_outline(roof, plan, tol);
  if (!outline) return std::nullopt;
  if (!floor.empty()) {
    const auto base = horizontal_outline(floor, plan, tol);
    if (!base || !same_ring(*outline, *base, tol)) return std::nullopt;
  }

  // Each side triangle on exactly one outline edge (the first that holds all its plan points).
  const std::vector<Vec2>& ring = *outline;
  const std::size_t n = ring.size();
  std::vector<std::vector<WallTriangle>> walls(n);
  for (const Triangle& t : sides) {
    Box2 box;
    for (std::uint32_t v : t) box.extend(plan[v]);
    bool placed = false;
    for (std::size_t e = 0; e < n && !placed; ++e) {
      const Vec2 a = ring[e], b = ring[(e + 1) % n];
      if (std::min(a.x, b.x) - tol > box.hi.x || std::max(a.x, b.x) + tol < box.lo.x ||
          std::min(a.y, b.y) - tol > box.hi.y || std::max(a.y, b.y) + tol < box.lo.y)
        continue;
      if (distance_to_segment(plan[t[0]], a, b) > tol || distance_to_segment(plan[t[1]], a, b) > tol ||
          distance_to_segment(plan[t[2]], a, b) > tol)
        continue;
      const Vec2 d = b - a;
      const double len = length(d);
      WallTriangle w{t, {}};
      for (int k = 0; k < 3; ++k) w.s[k] = dot(plan[t[k]] - a, d) / len;
      walls[e].push_back(w);
      placed = true;
    }
    if (!placed) return std::nullopt;  // not vertical, or not on the outline
  }
  for (std::size_t e = 0; e < n; ++e)
    if (!covers_rectangle(walls[e], vertices, length(ring[(e + 1) % n] - ring[e]), h, tol)) return std::nullopt;

  Building b;
  b.id = mesh.id;
  b.footprint = ring;
  b.height = h;
  try {
    validate_and_finish(b);
  } catch (const InputError&) {
    return std::nullopt;
  }
  return b;
}

}  // namespace cullcheck::formats
