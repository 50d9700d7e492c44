// Irregular city: rotated non-convex footprints (L, U, T) and convex polygons, no overlaps.
#include <algorithm>
#include <nlohmann/json.hpp>

#include "core/scene_io.hpp"
#include "generators/city.hpp"
#include "generators/param_checks.hpp"
#include "generators/params_json.hpp"
#include "generators/rejection_placement.hpp"

namespace cullcheck::generators {
namespace {

constexpr std::uint64_t kIrregularStream = 0x49525247;  // "IRRG"

double draw_length(Random& rng, double lo, double hi) { return metres(rng.uniform_int(to_mm(lo), to_mm(hi))); }

// A wing width in [min_arm, limit], limit being what the shape leaves for it.
double draw_arm(Random& rng, double min_arm, double limit) { return draw_length(rng, min_arm, std::max(min_arm, limit)); }

// Convex polygon: k vertices at increasing ellipse positions, one per equal slot with jitter up
// to 40% of a slot, so neighbouring vertices never coincide on the 1 mm grid.
Ring convex_polygon(Random& rng, double w, double d, int k) {
  std::vector<double> positions;
  const double slot = 4.0 / k;
  const double phase = rng.uniform01() * slot;
  for (int i = 0; i < k; ++i) {
    double u = phase + slot * (i + rng.uniform_real(-0.4, 0.4));  // in [-0.4 slot, 4 + 0.4 slot)
    if (u < 0.0) u += 4.0;
    if (u >= 4.0) u -= 4.0;
    positions.push_back(u);
  }
  std::sort(positions.begin(), positions.end());
  return ellipse_ring(w, d, positions);
}

Ring local_shape(Random& rng, const IrregularParams& p, double w, double d) {
  const double weights[5] = {p.rectangle_weight, p.l_shape_weight, p.u_shape_weight, p.t_shape_weight, p.convex_weight};
  double total = 0;
  for (double x : weights) total += x;
  double pick = rng.uniform01() * total;
  int shape = 0;
  while (shape < 4 && (weights[shape] == 0.0 || pick >= weights[shape])) pick -= weights[shape], ++shape;
  const double arm = p.min_arm_width;
  // The arm across the depth is drawn before the one across the width: the order the pinned digests
  // (generators/tests/pinned_streams_test.cpp) recorded when both draws sat in one call's
  // arguments, whose order of evaluation C++ leaves open (gcc went right to left).
  double across_d = 0, across_w = 0;
  if (shape >= 1 && shape <= 3) {
    across_d = draw_arm(rng, arm, d - arm);
    across_w = draw_arm(rng, arm, shape == 1 ? w - arm : shape == 2 ? (w - arm) / 2 : w - 2 * arm);
  }
  switch (shape) {
    case 1: return l_shape_ring(w, d, across_w, across_d);
    case 2: return u_shape_ring(w, d, across_w, across_d);
    case 3: return t_shape_ring(w, d, across_w, across_d);
    case 4: return convex_polygon(rng, w, d, static_cast<int>(rng.uniform_int(p.convex_min_vertices, p.convex_max_vertices)));
    default: return rectangle_ring(w, d);
  }
}

}  // namespace

void validate(const IrregularParams& p, const std::string& generator) {
  const ParamChecks check("generator", generator);
  check.in_range("count", p.count, 0, 1'000'000);
  check.in_range("area_size", p.area_size, 1.0, 1.0e6);
  check.in_range("min_arm_width", p.min_arm_width, 0.1, 1000.0);
  // Every shape must fit its wings: a U needs two arms and a notch across its width.
  check.in_range("min_size", p.min_size, 3 * p.min_arm_width, p.area_size);
  check.in_range("max_size", p.max_size, p.min_size, p.area_size);
  check.above("min_height", p.min_height, 0.0, kMaxHeight);
  check.in_range("max_height", p.max_height, p.min_height, kMaxHeight);
  check.in_range("rotated_fraction", p.rotated_fraction, 0.0, 1.0);
  check.in_range("rectangle_weight", p.rectangle_weight, 0.0, 1.0e6);
  check.in_range("l_shape_weight", p.l_shape_weight, 0.0, 1.0e6);
  check.in_range("u_shape_weight", p.u_shape_weight, 0.0, 1.0e6);
  check.in_range("t_shape_weight", p.t_shape_weight, 0.0, 1.0e6);
  check.in_range("convex_weight", p.convex_weight, 0.0, 1.0e6);
  if (p.rectangle_weight + p.l_shape_weight + p.u_shape_weight + p.t_shape_weight + p.convex_weight <= 0.0)
    check.fail("rectangle_weight", "at least one shape weight must be > 0");
  // At most 32 vertices keeps neighbours >= 2 degrees apart, far more than rounding to 1 mm moves
  // them on metre-sized footprints (a ring that rounding bends is still simple, and partitioned).
  check.in_range("convex_min_vertices", p.convex_min_vertices, 3, 32);
  check.in_range("convex_max_vertices", p.convex_max_vertices, p.convex_min_vertices, 32);
  check.in_range("min_gap", p.min_gap, 0.0, 1000.0);
  check.in_range("max_attempts", p.max_attempts, 1, 10000);
}

Scene irregular_city(const IrregularParams& p, std::uint64_t seed) {
  validate(p);
  Scene scene;
  scene.provenance = {"irregular", seed, params_to_json(p).dump()};
  Random rng = Random::stream(seed, kIrregularStream);
  PlacementLimits limits{p.count, p.max_attempts, p.area_size, p.min_gap, 2 * p.max_size + 0.01};
  place_without_overlaps(scene, limits, rng, [&](Random& r) {
    const double w = draw_length(r, p.min_size, p.max_size), d = draw_length(r, p.min_size, p.max_size);
    const Ring local = local_shape(r, p, w, d);
    const PlanarRotation rot = draw_rotation(r, p.rotated_fraction);
    const Vec2 centre = draw_centre(r, p.area_size);
    return Candidate{place_on_grid(local, rot, centre), draw_length(r, p.min_height, p.max_height)};
  });
  return scene;
}

}  // namespace cullcheck::generators
