// Random scatter of rotated rectangles without overlaps (see city.hpp).
#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>

#include "core/scene_io.hpp"
#include "generators/city.hpp"
#include "generators/param_checks.hpp"
#include "generators/params_json.hpp"
#include "generators/rejection_placement.hpp"

namespace cullcheck::generators {
namespace {

constexpr std::uint64_t kScatterStream = 0x53434154;  // "SCAT"

double draw_length(Random& rng, double lo, double hi) { return metres(rng.uniform_int(to_mm(lo), to_mm(hi))); }

}  // namespace

void validate(const ScatterParams& p, const std::string& generator) {
  const ParamChecks check("generator", generator);
  check.in_range("count", p.count, 0, 1'000'000);
  check.in_range("area_size", p.area_size, 1.0, 1.0e6);
  check.in_range("min_size", p.min_size, 0.01, p.area_size);
  check.in_range("max_size", p.max_size, p.min_size, p.area_size);
  check.above("min_height", p.min_height, 0.0, kMaxHeight);
  check.in_range("max_height", p.max_height, p.min_height, kMaxHeight);
  check.in_range("rotated_fraction", p.rotated_fraction, 0.0, 1.0);
  check.in_range("thin_fraction", p.thin_fraction, 0.0, 1.0);
  check.in_range("thin_min_width", p.thin_min_width, 0.01, p.area_size);
  check.in_range("thin_max_width", p.thin_max_width, p.thin_min_width, p.area_size);
  check.in_range("min_gap", p.min_gap, 0.0, 1000.0);
  check.in_range("max_attempts", p.max_attempts, 1, 10000);
}

Scene scatter_city(const ScatterParams& p, std::uint64_t seed) {
  validate(p);
  Scene scene;
  scene.provenance = {"scatter", seed, params_to_json(p).dump()};
  Random rng = Random::stream(seed, kScatterStream);
  PlacementLimits limits{p.count, p.max_attempts, p.area_size, p.min_gap, 0.0};
  // A rotated w x d rectangle fits in a square of side w + d (|cos| + |sin| <= sqrt 2 < 2).
  limits.max_extent = std::max(p.max_size, p.thin_max_width) * 2 + 0.01;
  place_without_overlaps(scene, limits, rng, [&](Random& r) {
    const double w = draw_length(r, p.min_size, p.max_size);
    const double d = r.bernoulli(p.thin_fraction) ? draw_length(r, p.thin_min_width, p.thin_max_width)
                                                  : draw_length(r, p.min_size, p.max_size);
    const PlanarRotation rot = draw_rotation(r, p.rotated_fraction);
    const Vec2 centre = draw_centre(r, p.area_size);
    return Candidate{place_on_grid(rectangle_ring(w, d), rot, centre), draw_length(r, p.min_height, p.max_height)};
  });
  return scene;
}

}  // namespace cullcheck::generators
