#include "oracle/surface_samples.hpp"

#include <algorithm>
#include <cmath>

namespace cullcheck::oracle {
namespace {

// Grid intervals along a face dimension of length `length`.
std::size_t intervals(double length, double spacing, int minimum) {
  const double n = std::ceil(length / spacing);
  return std::max<std::size_t>(std::size_t(std::max(minimum, 1)), n > 1e6 ? std::size_t(1e6) : std::size_t(n));
}

// {0, inset, 1/n, ..., (n-1)/n, 1 - inset, 1}: the grid plus the inset copies of its ends.
std::vector<double> axis_params(std::size_t n, double inset) {
  std::vector<double> u{0.0, inset};
  for (std::size_t k = 1; k < n; ++k) u.push_back(double(k) / double(n));
  u.push_back(1.0 - inset);
  u.push_back(1.0);
  return u;
}

void wall_samples(Vec2 p, Vec2 q, double height, const SamplingOptions& o, double spacing, std::vector<Vec3>& out) {
  const double width = length(q - p);
  const std::size_t ns = intervals(width, spacing, o.face_grid), nt = intervals(height, spacing, o.face_grid);
  const std::size_t ms = std::max(ns, intervals(width, spacing, o.edge_samples));
  const std::size_t mt = std::max(nt, intervals(height, spacing, o.edge_samples));
  auto at = [&](double s, double t) {
    const Vec2 xy = p + (q - p) * s;
    out.push_back({xy.x, xy.y, height * t});
  };
  const std::vector<double> S = axis_params(ns, o.inset), T = axis_params(nt, o.inset);
  for (double t : T)
    for (double s : S) at(s, t);
  // Denser samples along the face's edges (silhouette candidates) when edge_samples asks for them.
  const double rims[4] = {0.0, o.inset, 1.0 - o.inset, 1.0};
  if (ms > ns)
    for (double t : rims)
      for (double s : axis_params(ms, o.inset)) at(s, t);
  if (mt > nt)
    for (double s : rims)
      for (double t : axis_params(mt, o.inset)) at(s, t);
}

void roof_samples(const std::vector<Vec2>& ring, double height, const SamplingOptions& o, double spacing,
                  std::vector<Vec3>& out) {
  Box2 box;
  Vec2 centroid;
  for (Vec2 v : ring) box.extend(v), centroid = centroid + v;
  centroid = centroid * (1.0 / double(ring.size()));
  const std::size_t n = ring.size();
  // Boundary: every edge at {0, inset, 1/m, ..., 1 - inset} (its end is the next edge's start),
  // each point on the edge and moved toward the centroid.
  for (std::size_t k = 0; k < n; ++k) {
    const Vec2 a = ring[k], b = ring[(k + 1) % n];
    const double len = length(b - a);
    const std::size_t m = std::max(intervals(len, spacing, o.face_grid), intervals(len, spacing, o.edge_samples));
    std::vector<double> u = axis_params(m, o.inset);
    u.pop_back();  // 1 is the next edge's 0
    for (double s : u) {
      const Vec2 e = a + (b - a) * s;
      const Vec2 inward = e + (centroid - e) * o.inset;
      out.push_back({e.x, e.y, height});
      out.push_back({inward.x, inward.y, height});
    }
  }
  // Interior: grid nodes of the piece's bounding box that lie strictly inside the convex ring.
  const std::size_t nx = intervals(box.hi.x - box.lo.x, spacing, o.face_grid);
  const std::size_t ny = intervals(box.hi.y - box.lo.y, spacing, o.face_grid);
  for (std::size_t j = 1; j < ny; ++j) {
    for (std::size_t i = 1; i < nx; ++i) {
      const Vec2 g{box.lo.x + (box.hi.x - box.lo.x) * double(i) / double(nx),
                   box.lo.y + (box.hi.y - box.lo.y) * double(j) / double(ny)};
      bool inside = true;
      for (std::size_t k = 0; k < n && inside; ++k) inside = cross(ring[(k + 1) % n] - ring[k], g - ring[k]) > 0.0;
      if (inside) out.push_back({g.x, g.y, height});
    }
  }
}

// A building with the oracle's roof triangles (mesh.hpp), the roof pieces sampled.
struct RoofedBuilding {
  const Building& building;
  const RoofTriangles& roof;
};

void samples_at(const RoofedBuilding& r, const SamplingOptions& o, double spacing, std::vector<Vec3>& out) {
  out.clear();
  const Building& b = r.building;
  const std::size_t n = b.footprint.size();
  for (std::size_t k = 0; k < n; ++k) wall_samples(b.footprint[k], b.footprint[(k + 1) % n], b.height, o, spacing, out);
  for (const auto& t : r.roof) roof_samples({b.footprint[t[0]], b.footprint[t[1]], b.footprint[t[2]]}, b.height, o, spacing, out);
}

void samples_at(const MeshObject& m, const SamplingOptions& o, double spacing, std::vector<Vec3>& out) {
  out.clear();
  for (const auto& t : m.triangles) {
    const Vec3 v[3] = {m.vertices[t[0]], m.vertices[t[1]], m.vertices[t[2]]};
    const Vec3 centroid = (v[0] + v[1] + v[2]) * (1.0 / 3.0);
    const double longest = std::max({length(v[1] - v[0]), length(v[2] - v[1]), length(v[0] - v[2])});
    const std::size_t n = std::max(intervals(longest, spacing, o.face_grid), intervals(longest, spacing, o.edge_samples));
    // Boundary: each edge from its start vertex up to (not including) the next vertex.
    for (int e = 0; e < 3; ++e) {
      const Vec3 a = v[e], b = v[(e + 1) % 3];
      for (std::size_t k = 0; k < n; ++k) {
        const Vec3 p = a + (b - a) * (double(k) / double(n));
        out.push_back(p);
        out.push_back(p + (centroid - p) * o.inset);
      }
    }
    // Interior nodes of the barycentric grid.
    for (std::size_t i = 1; i < n; ++i)
      for (std::size_t j = 1; i + j < n; ++j)
        out.push_back(v[0] + (v[1] - v[0]) * (double(i) / double(n)) + (v[2] - v[0]) * (double(j) / double(n)));
  }
}

// Widens the spacing until the cap holds, or until every face is at its minimum grid (spacing
// beyond the object's largest dimension changes nothing more).
template <class Object>
void capped_samples(const Object& object, const SamplingOptions& options, double largest, SurfaceSamples& s) {
  s.spacing_m = options.spacing_m;
  s.capped = false;
  samples_at(object, options, s.spacing_m, s.points);
  if (s.points.size() <= options.max_samples_per_building) return;
  // The count never grows with the spacing, so when even the coarsest spacing the loop below can
  // reach misses the cap, the loop would end there: go there at once (an object of many faces,
  // e.g. an imported model, would otherwise be sampled dozens of times over).
  double coarsest = s.spacing_m;
  while (coarsest <= largest) coarsest *= 1.25;
  if (coarsest != s.spacing_m) {
    std::vector<Vec3> points;
    samples_at(object, options, coarsest, points);
    if (points.size() > options.max_samples_per_building) {
      s.points = std::move(points), s.spacing_m = coarsest, s.capped = true;
      return;
    }
  }
  while (s.points.size() > options.max_samples_per_building && s.spacing_m <= largest) {
    s.capped = true;
    s.spacing_m *= 1.25;
    samples_at(object, options, s.spacing_m, s.points);
  }
}

}  // namespace

void surface_samples(const MeshObject& mesh, const SamplingOptions& options, SurfaceSamples& out) {
  const Box3& box = mesh.bounds;
  capped_samples(mesh, options, std::max({box.hi.x - box.lo.x, box.hi.y - box.lo.y, box.hi.z - box.lo.z}), out);
}

void surface_samples(const Building& building, const RoofTriangles& roof, const SamplingOptions& options, SurfaceSamples& out) {
  capped_samples(RoofedBuilding{building, roof}, options,
                 std::max({building.bounds.hi.x - building.bounds.lo.x, building.bounds.hi.y - building.bounds.lo.y, building.height}),
                 out);
}

SurfaceSamples surface_samples(const MeshObject& mesh, const SamplingOptions& options) {
  SurfaceSamples s;
  surface_samples(mesh, options, s);
  return s;
}

SurfaceSamples surface_samples(const Building& building, const RoofTriangles& roof, const SamplingOptions& options) {
  SurfaceSamples s;
  surface_samples(building, roof, options, s);
  return s;
}

}  // namespace cullcheck::oracle
