// Sample points on an object's surface, the targets of the ray oracle's surface rays
// (design: "vertices, edge points, a grid on each face, silhouette points").
//
// Buildings:
// Walls are parametrised by (s, t) in [0, 1]^2 (s along the footprint edge, t up the wall);
// each axis is sampled at {0, inset, 1/n, ..., (n-1)/n, 1 - inset, 1}, so the grid holds the
// vertices (top and bottom corners), points on every edge, a grid on the face, and copies of
// the edge and corner points moved into the face by `inset`. Roof pieces (the oracle's roof
// triangles, roof_triangulation.hpp, at the roof height) get a grid of interior points plus
// points along their boundary, each also moved toward the piece's centroid by `inset`.
//
// Mesh objects, per triangle (a, b, c): points along each edge (its start vertex included) at
// max(face_grid, edge_samples, ceil(length / spacing)) intervals, the longest edge's count for
// all three edges, each also moved toward the triangle's centroid by `inset` (relative: the
// point p + (centroid - p) * inset); then the interior nodes of the barycentric grid of that
// many intervals, a + (b - a) i / n + (c - a) j / n with i, j >= 1, i + j < n. Points shared by
// neighbouring triangles are sampled once per triangle (duplicates cost rays, nothing else).
//
// The per-object cap (max_samples_per_building) widens the spacing by 1.25 at a time until the
// samples fit or every face is at its minimum grid (spacing beyond the object's largest
// dimension changes nothing more); so an object with very many faces may keep more samples than
// the cap, and says so with `capped`. The order is fixed, so the same object and options always
// give the same samples.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "core/scene.hpp"
#include "oracle/sampling.hpp"

namespace cullcheck::oracle {

struct SurfaceSamples {
  std::vector<Vec3> points;
  double spacing_m = 0.0;  // the spacing used: options.spacing_m, or wider if capped
  bool capped = false;     // true when the per-object cap widened the spacing
};

// A building's roof triangles as indices into its footprint (TriangleMesh::roofs).
using RoofTriangles = std::vector<std::array<std::uint32_t, 3>>;

SurfaceSamples surface_samples(const Building& building, const RoofTriangles& roof, const SamplingOptions& options);
SurfaceSamples surface_samples(const MeshObject& mesh, const SamplingOptions& options);
// The same into `out`, reusing its memory (the ray plan samples one object after another).
void surface_samples(const Building& building, const RoofTriangles& roof, const SamplingOptions& options, SurfaceSamples& out);
void surface_samples(const MeshObject& mesh, const SamplingOptions& options, SurfaceSamples& out);

}  // namespace cullcheck::oracle
