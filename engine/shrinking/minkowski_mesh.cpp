#include "engine/shrinking/minkowski_mesh.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <stdexcept>
#include <string>
#include <utility>

namespace cullcheck {
namespace {

constexpr double kSameNormal = 1.0 - 1e-12;  // dot of unit normals above this: one plane direction
constexpr double kGroundTolerance = 1e-9;    // metres
constexpr double kMinCosine = 1e-9;          // below this a vertex has no finite δ

Box3 box_of(const std::array<Vec3, 6>& points) {
  Box3 b;
  for (Vec3 p : points) b.extend(p);
  return b;
}

bool boxes_overlap(const Box3& a, const Box3& b) {
  return a.lo.x <= b.hi.x && b.lo.x <= a.hi.x && a.lo.y <= b.hi.y && b.lo.y <= a.hi.y && a.lo.z <= b.hi.z &&
         b.lo.z <= a.hi.z;
}

// Whether the convex hulls of two six-point sets overlap deeper than `tolerance`. Separating-axis
// test: two convex polytopes are disjoint iff some face normal of either, or some cross product of
// an edge of one with an edge of the other, separates their projections. Every hull face is
// spanned by three of its points and every hull edge joins two of them, so testing the normals of
// all point triples and the cross products of all point-pair directions covers those axes (the
// extra axes can only find a separation that really exists). Degenerate (flat) hulls are covered
// the same way.
bool hulls_overlap(const std::array<Vec3, 6>& a, const std::array<Vec3, 6>& b, double tolerance) {
  auto separates = [&](Vec3 axis) {
    const double len = length(axis);
    if (!(len > 1e-300)) return false;
    axis = axis * (1.0 / len);
    double a_lo = HUGE_VAL, a_hi = -HUGE_VAL, b_lo = HUGE_VAL, b_hi = -HUGE_VAL;
    for (Vec3 p : a) a_lo = std::min(a_lo, dot(p, axis)), a_hi = std::max(a_hi, dot(p, axis));
    for (Vec3 p : b) b_lo = std::min(b_lo, dot(p, axis)), b_hi = std::max(b_hi, dot(p, axis));
    return a_hi <= b_lo + tolerance || b_hi <= a_lo + tolerance;
  };
  std::vector<Vec3> a_dirs, b_dirs;
  for (const auto* hull : {&a, &b}) {
    auto& dirs = hull == &a ? a_dirs : b_dirs;
    for (int i = 0; i < 6; ++i)
      for (int j = i + 1; j < 6; ++j) {
        dirs.push_back((*hull)[j] - (*hull)[i]);
        for (int k = j + 1; k < 6; ++k)
          if (separates(cross((*hull)[j] - (*hull)[i], (*hull)[k] - (*hull)[i]))) return false;
      }
  }
  for (Vec3 u : a_dirs)
    for (Vec3 v : b_dirs)
      if (separates(cross(u, v))) return false;
  return true;
}

}  // namespace

Vec3 TriangleMesh::normal(std::size_t t) const {
  const auto& [i, j, k] = triangles[t];
  const Vec3 n = cross(vertices[j] - vertices[i], vertices[k] - vertices[i]);
  const double len = length(n);
  return len > 0.0 ? n * (1.0 / len) : Vec3{};
}

ShrunkMesh shrink_mesh(const TriangleMesh& mesh, double epsilon, double ground_z) {
  const std::size_t nv = mesh.vertices.size(), nt = mesh.triangles.size();
  ShrunkMesh out;
  out.stats.faces_in = nt;
  out.delta.assign(nv, 0.0);
  out.mesh.vertices = mesh.vertices;

  Box3 extent_box;
  for (Vec3 p : mesh.vertices) extent_box.extend(p);
  const double extent =
      nv == 0 ? 1.0
              : std::max({extent_box.hi.x - extent_box.lo.x, extent_box.hi.y - extent_box.lo.y,
                          extent_box.hi.z - extent_box.lo.z, 1e-3}) +
                    2.0 * epsilon;

  auto on_ground = [&](std::uint32_t v) { return std::abs(mesh.vertices[v].z - ground_z) <= kGroundTolerance; };
  std::vector<Vec3> normals(nt);
  std::vector<bool> floor(nt);
  for (std::size_t t = 0; t < nt; ++t) {
    normals[t] = mesh.normal(t);
    const auto& tri = mesh.triangles[t];
    floor[t] = on_ground(tri[0]) && on_ground(tri[1]) && on_ground(tri[2]);
  }

  // Distinct normals of the (non-floor, non-degenerate) faces around each vertex.
  std::vector<std::vector<Vec3>> around(nv);
  for (std::size_t t = 0; t < nt; ++t) {
    if (floor[t] || length(normals[t]) == 0.0) continue;
    for (std::uint32_t v : mesh.triangles[t]) {
      auto& list = around[v];
      if (std::none_of(list.begin(), list.end(), [&](Vec3 n) { return dot(n, normals[t]) > kSameNormal; }))
        list.push_back(normals[t]);
    }
  }

  std::vector<bool> unshrinkable(nv, false);
  for (std::uint32_t v = 0; v < nv; ++v) {
    const auto& list = around[v];
    if (list.empty()) continue;  // touches only floor or degenerate faces: nothing to move
    Vec3 direction = std::accumulate(list.begin(), list.end(), Vec3{});
    if (on_ground(v)) direction.z = 0.0;  // Fig. 16: a ground vertex moves horizontally only
    const double len = length(direction);
    if (!(len > kMinCosine)) {
      unshrinkable[v] = true;
      continue;
    }
    direction = direction * (1.0 / len);
    // sin(α/2) = sin(90° - max angle) = min cos(angle(N_v, N_i)).
    double sin_half_alpha = HUGE_VAL;
    for (Vec3 n : list) sin_half_alpha = std::min(sin_half_alpha, dot(direction, n));
    if (!(sin_half_alpha > kMinCosine)) {
      unshrinkable[v] = true;
      continue;
    }
    const double delta = epsilon / sin_half_alpha;
    out.delta[v] = delta;
    out.mesh.vertices[v] = mesh.vertices[v] - direction * delta;
    out.stats.max_delta = std::max(out.stats.max_delta, delta);
  }

  // Faces that cannot stay: around an unshrinkable vertex, zero area or turned over once moved.
  std::vector<bool> removed(nt, false);
  const double min_double_area = 1e-12 * extent * extent;
  for (std::size_t t = 0; t < nt; ++t) {
    const auto& [i, j, k] = mesh.triangles[t];
    const auto& m = out.mesh.vertices;
    const Vec3 moved = cross(m[j] - m[i], m[k] - m[i]);
    removed[t] = true;
    if (length(normals[t]) == 0.0) {
      ++out.stats.degenerate_dropped;
    } else if (unshrinkable[i] || unshrinkable[j] || unshrinkable[k]) {
      ++out.stats.unshrinkable_removed;
    } else if (!(length(moved) > min_double_area)) {
      ++out.stats.zero_area_removed;
    } else if (!(dot(moved, normals[t]) > 0.0)) {
      ++out.stats.flipped_removed;
    } else {
      removed[t] = false;
    }
  }

  // Movement volumes of the faces still kept; pairs found by a sweep over the boxes' x ranges.
  std::vector<std::array<Vec3, 6>> volume(nt);
  std::vector<Box3> box(nt);
  std::vector<std::uint32_t> order;
  for (std::uint32_t t = 0; t < nt; ++t) {
    if (removed[t]) continue;
    const auto& tri = mesh.triangles[t];
    for (int c = 0; c < 3; ++c) volume[t][c] = mesh.vertices[tri[c]], volume[t][c + 3] = out.mesh.vertices[tri[c]];
    box[t] = box_of(volume[t]);
    order.push_back(t);
  }
  std::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) { return box[a].lo.x < box[b].lo.x; });
  std::vector<bool> collided(nt, false);
  const double touch = 1e-9 * extent;
  for (std::size_t p = 0; p < order.size(); ++p) {
    const std::uint32_t s = order[p];
    for (std::size_t q = p + 1; q < order.size() && box[order[q]].lo.x <= box[s].hi.x; ++q) {
      const std::uint32_t t = order[q];
      const auto& a = mesh.triangles[s];
      const auto& b = mesh.triangles[t];
      const bool neighbours = std::any_of(a.begin(), a.end(), [&](std::uint32_t v) {
        return std::find(b.begin(), b.end(), v) != b.end();
      });
      if (neighbours || !boxes_overlap(box[s], box[t])) continue;
      ++out.stats.pairs_tested;
      if (hulls_overlap(volume[s], volume[t], touch)) collided[s] = collided[t] = true;
    }
  }
  for (std::size_t t = 0; t < nt; ++t) {
    if (collided[t]) removed[t] = true, ++out.stats.collisions_removed;
    if (removed[t]) {
      if (length(normals[t]) != 0.0) ++out.stats.faces_removed;
    } else {
      out.mesh.triangles.push_back(mesh.triangles[t]);
    }
  }
  return out;
}

TriangleMesh building_mesh(const Building& building) {
  const std::vector<Vec2>& ring = building.footprint;
  const std::uint32_t n = static_cast<std::uint32_t>(ring.size());
  if (n < 3 || building.prisms.empty())
    throw std::invalid_argument("building " + std::to_string(building.id) + ": footprint and prisms required (finish_building)");
  TriangleMesh mesh;
  for (Vec2 p : ring) mesh.vertices.push_back({p.x, p.y, 0.0});
  for (Vec2 p : ring) mesh.vertices.push_back({p.x, p.y, building.height});
  for (std::uint32_t i = 0; i < n; ++i) {
    const std::uint32_t j = (i + 1) % n;
    // Counter-clockwise seen from outside (outside is right of the counter-clockwise footprint).
    mesh.triangles.push_back({i, j, n + j});
    mesh.triangles.push_back({i, n + j, n + i});
  }
  // The convex partition reuses footprint vertices exactly (core/convex_partition.hpp), so each
  // prism corner is found among them and the roof shares the walls' top vertices.
  std::map<std::pair<double, double>, std::uint32_t> index;
  for (std::uint32_t i = 0; i < n; ++i) index.emplace(std::pair{ring[i].x, ring[i].y}, n + i);
  for (const ConvexVerticalPrism& prism : building.prisms) {
    std::vector<std::uint32_t> corners;
    for (Vec2 p : prism.ring) {
      const auto it = index.find({p.x, p.y});
      if (it == index.end())
        throw std::invalid_argument("building " + std::to_string(building.id) + ": prism corner not on the footprint");
      corners.push_back(it->second);
    }
    for (std::size_t k = 1; k + 1 < corners.size(); ++k) mesh.triangles.push_back({corners[0], corners[k], corners[k + 1]});
  }
  return mesh;
}

}  // namespace cullcheck
