#include "engine/shrinking/minkowski_shrinking.hpp"

#include <algorithm>
#include <cmath>

#include "engine/shrinking/minkowski_mesh.hpp"
#include "engine/shrinking/region_sweep.hpp"

namespace cullcheck {
namespace {

// Plan distance between two segments: zero when they cross, else the least of the four
// endpoint-to-segment distances.
double segment_distance(Vec2 a, Vec2 b, Vec2 c, Vec2 d) {
  const double o1 = cross(b - a, c - a), o2 = cross(b - a, d - a);
  const double o3 = cross(d - c, a - c), o4 = cross(d - c, b - c);
  if (((o1 > 0 && o2 < 0) || (o1 < 0 && o2 > 0)) && ((o3 > 0 && o4 < 0) || (o3 < 0 && o4 > 0))) return 0.0;
  return std::min({distance_to_segment(a, c, d), distance_to_segment(b, c, d), distance_to_segment(c, a, b),
                   distance_to_segment(d, a, b)});
}

// Crossing-number test; points on the boundary are excluded by the distance check anyway.
bool inside(const std::vector<Vec2>& ring, Vec2 p) {
  bool in = false;
  for (std::size_t i = 0, j = ring.size() - 1; i < ring.size(); j = i++) {
    const Vec2 a = ring[j], b = ring[i];
    if ((a.y > p.y) != (b.y > p.y) && p.x < a.x + (b.x - a.x) * (p.y - a.y) / (b.y - a.y)) in = !in;
  }
  return in;
}

// S ⊕ disc(ε) ⊆ O for the shrunk footprint S of the original O (see the header).
bool valid_shrunk_footprint(const std::vector<Vec2>& shrunk, const std::vector<Vec2>& original, double epsilon) {
  if (shrunk.size() < 3 || !(signed_area(shrunk) > 0.0) || !is_simple(shrunk)) return false;
  for (Vec2 p : shrunk)
    if (!inside(original, p)) return false;
  for (std::size_t i = 0, n = shrunk.size(); i < n; ++i)
    for (std::size_t j = 0, m = original.size(); j < m; ++j)
      if (!(segment_distance(shrunk[i], shrunk[(i + 1) % n], original[j], original[(j + 1) % m]) >= epsilon)) return false;
  return true;
}

}  // namespace

MinkowskiOccluder minkowski_occluder(const Building& building, double epsilon) {
  MinkowskiOccluder out;
  const ShrunkMesh shrunk = shrink_mesh(building_mesh(building), epsilon, 0.0);
  out.max_delta = shrunk.stats.max_delta;
  if (shrunk.stats.faces_removed > 0) {
    out.outcome = MinkowskiOutcome::faces_removed;
    return out;
  }
  const std::vector<Vec2>& ring = building.footprint;
  const std::size_t n = ring.size();
  const std::vector<Vec3>& moved = shrunk.mesh.vertices;  // [0, n) ground, [n, 2n) roof

  // Each wall's offset: the largest inward displacement of its four moved vertices (every one is
  // at least ε by construction; the largest keeps the whole moved wall behind the offset line).
  std::vector<Vec2> inward(n);
  std::vector<double> offset(n);
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t j = (i + 1) % n;
    const Vec2 d = ring[j] - ring[i];
    inward[i] = Vec2{-d.y, d.x} * (1.0 / length(d));  // left of a counter-clockwise edge
    double most = epsilon;
    for (std::size_t v : {i, j, n + i, n + j}) most = std::max(most, dot(plan(moved[v]) - ring[i], inward[i]));
    offset[i] = most * (1.0 + 1e-9) + 1e-9;
  }
  // Mitred joins: vertex i where the offset lines of edges i - 1 and i meet.
  out.footprint.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t h = (i + n - 1) % n;
    const Vec2 u = ring[i] - ring[h], w = ring[(i + 1) % n] - ring[i];
    const Vec2 a = ring[h] + inward[h] * offset[h], b = ring[i] + inward[i] * offset[i];
    const double denominator = cross(u, w);
    if (std::abs(denominator) <= 1e-12 * length(u) * length(w)) {
      // Collinear edges: a join exists only when both move alike.
      if (dot(u, w) <= 0.0 || offset[h] != offset[i]) {
        out.outcome = MinkowskiOutcome::invalid_footprint;
        return out;
      }
      out.footprint[i] = b;
    } else {
      out.footprint[i] = a + u * (cross(b - a, w) / denominator);
    }
  }
  out.height = HUGE_VAL;
  for (std::size_t v = n; v < 2 * n; ++v) out.height = std::min(out.height, moved[v].z);
  if (!(out.height > 0.0)) {
    out.outcome = MinkowskiOutcome::too_low;
    return out;
  }
  if (!valid_shrunk_footprint(out.footprint, ring, epsilon)) {
    out.outcome = MinkowskiOutcome::invalid_footprint;
    return out;
  }
  Building shrunk_building;
  shrunk_building.id = building.id;
  shrunk_building.footprint = out.footprint;
  shrunk_building.height = out.height;
  finish_building(shrunk_building);
  out.prisms = std::move(shrunk_building.prisms);
  out.outcome = MinkowskiOutcome::occluder;
  return out;
}

std::vector<ConvexVerticalPrism> MinkowskiShrinking::shrink(std::size_t b, double epsilon) {
  MinkowskiOccluder occluder = minkowski_occluder(scene_.buildings[b], epsilon);
  switch (occluder.outcome) {
    case MinkowskiOutcome::occluder: ++counts_.occluders; break;
    case MinkowskiOutcome::faces_removed: ++counts_.faces_removed; break;
    case MinkowskiOutcome::invalid_footprint: ++counts_.invalid_footprint; break;
    case MinkowskiOutcome::too_low: ++counts_.too_low; break;
  }
  return std::move(occluder.prisms);
}

}  // namespace cullcheck
