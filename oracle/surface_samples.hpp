// Sample points on a building's surface, the targets of the ray oracle's surface rays
// (design: "vertices, edge points, a grid on each face, silhouette points").
//
// Walls are parametrised by (s, t) in [0, 1]^2 (s along the footprint edge, t up the wall);
// each axis is sampled at {0, inset, 1/n, ..., (n-1)/n, 1 - inset, 1}, so the grid holds the
// vertices (top and bottom corners), points on every edge, a grid on the face, and copies of
// the edge and corner points moved into the face by `inset`. Roof pieces (the building's convex
// prisms at the roof height) get a grid of interior points plus points along their boundary,
// each also moved toward the piece's centroid by `inset`. The order is fixed, so the same
// building and options always give the same samples.
#pragma once

#include <vector>

#include "core/scene.hpp"
#include "oracle/sampling.hpp"

namespace cullcheck::oracle {

struct SurfaceSamples {
  std::vector<Vec3> points;
  double spacing_m = 0.0;  // the spacing used: options.spacing_m, or wider if capped
  bool capped = false;     // true when the per-building cap widened the spacing
};

SurfaceSamples surface_samples(const Building& building, const SamplingOptions& options);

}  // namespace cullcheck::oracle
