// Sampling density of the ray oracle (design: "Oracle"; reports state it next to every count).
//
// The witnessed set is a lower bound of the true visible set; these knobs say how dense the
// rays are, so a report can say how close to the true set the bound is expected to be.
#pragma once

#include <cstddef>
#include <cstdint>
#include <nlohmann/json_fwd.hpp>

namespace cullcheck::oracle {

struct SamplingOptions {
  // Surface samples, per face of every candidate object (a building's walls and roof pieces, a
  // mesh object's triangles; surface_samples.hpp). Along each face dimension of length L the
  // grid has max(face_grid, ceil(L / spacing_m)) intervals; the face's edges (including the
  // vertices) get max(edge_samples, that) intervals.
  double spacing_m = 2.0;
  int face_grid = 4;
  int edge_samples = 4;
  // Samples that sit exactly on an edge aim a ray that grazes the object; each edge and corner
  // sample also has a copy moved into the face by `inset` (relative to the face's size), whose
  // ray hits the face unambiguously.
  double inset = 1e-4;
  // When an object (a building or a mesh object) would get more samples than this, its spacing
  // is widened until it fits (surface_samples.hpp says when it cannot).
  std::size_t max_samples_per_building = 4096;
  // Silhouette-grazing rays (ray_plan.hpp): along every silhouette edge of every candidate
  // object (a building's vertical and roof edges where a face toward the eye meets one away from
  // it; a mesh object's boundary edges and edges between triangles facing either way), at the edge-sample spacing, one ray just beside the edge on each side, passing it at
  // graze_offset times the distance from the eye (radians; for an orthographic camera, times the
  // larger side of its view box), and at least 1e-6 of the point's distance from the mesh origin
  // (16 float ulps, so that Embree's answer is not decided by rounding). 0 disables them.
  double graze_offset = 1e-5;
  // Stratified rays over the view volume: a jittered grid of `frustum_resolution` columns over
  // the image plane (rows in proportion to the aspect ratio, at most 4N); an orthographic
  // camera's grid covers its ortho_width x ortho_height rectangle the same way (parallel rays
  // from the near plane); omnidirectional cameras get 2N azimuth columns by N rows, equal-area
  // (uniform in sin(elevation)). 0 disables them.
  int frustum_resolution = 256;
  // Stop casting an object's surface-sample rays once they have found every witness of it the
  // oracle keeps (the first and kFurtherWitnesses more; checked every 16 rays). Its grazing rays
  // are still cast: they witness what lies behind it. The skipped rays could have had another
  // object in front of the sample as their first hit, so this may drop a witness of that object
  // which no other ray finds: measured in README's "Oracle speed".
  bool stop_when_witnessed = true;
  // Seed of the jitter PRNG (SplitMix64, implemented in the oracle: the same seed gives the
  // same rays on every platform).
  std::uint64_t seed = 0x5eed5eedULL;
  // Threads casting rays. Results are merged in ray order, so they do not depend on this.
  int threads = 2;

  friend bool operator==(const SamplingOptions&, const SamplingOptions&) = default;
};

// Throws InputError naming the field if an option is out of range.
void validate(const SamplingOptions& o);

void to_json(nlohmann::json& j, const SamplingOptions& o);
void from_json(const nlohmann::json& j, SamplingOptions& o);

}  // namespace cullcheck::oracle
