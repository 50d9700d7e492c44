#include "generators/terrain_gen.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "generators/param_checks.hpp"
#include "generators/params_json.hpp"
#include "generators/random.hpp"

namespace cullcheck::generators {
namespace {

constexpr std::uint64_t kTerrainTag = 0x7465727261696eULL;  // "terrain"
constexpr std::uint64_t kHoleTag = 0x686f6c65ULL;            // "hole"

// A uniform draw in [-1, 1) keyed by the vertex and the seed, not by draw order: the same
// vertex gets the same displacement whatever order the passes visit it in.
double displacement(std::uint64_t seed, std::size_t i, std::size_t j) {
  return 2.0 * Random::stream(seed, kTerrainTag, i, j).uniform01() - 1.0;
}

// Diamond-square on an n x n grid, n = 2^k + 1; heights in arbitrary units.
std::vector<double> diamond_square(std::size_t n, double roughness, std::uint64_t seed) {
  std::vector<double> h(n * n, 0.0);
  const auto at = [&](std::size_t i, std::size_t j) -> double& { return h[j * n + i]; };
  double amplitude = 1.0;
  for (std::size_t i : {std::size_t(0), n - 1})
    for (std::size_t j : {std::size_t(0), n - 1}) at(i, j) = amplitude * displacement(seed, i, j);
  for (std::size_t step = n - 1; step > 1; step /= 2) {
    const std::size_t half = step / 2;
    // Diamond: each square's centre from its four corners.
    for (std::size_t j = half; j < n; j += step)
      for (std::size_t i = half; i < n; i += step)
        at(i, j) = 0.25 * (at(i - half, j - half) + at(i + half, j - half) + at(i - half, j + half) + at(i + half, j + half)) +
                   amplitude * displacement(seed, i, j);
    // Square: each edge midpoint from its (three or four) neighbours.
    for (std::size_t j = 0; j < n; j += half)
      for (std::size_t i = (j / half) % 2 == 0 ? half : 0; i < n; i += step) {
        double sum = 0.0;
        int count = 0;
        if (i >= half) sum += at(i - half, j), ++count;
        if (i + half < n) sum += at(i + half, j), ++count;
        if (j >= half) sum += at(i, j - half), ++count;
        if (j + half < n) sum += at(i, j + half), ++count;
        at(i, j) = sum / count + amplitude * displacement(seed, i, j);
      }
    amplitude *= roughness;
  }
  return h;
}

// Maps the values onto [0, 1] (all zero when they are all equal).
void normalise(std::vector<double>& v) {
  const auto [lo, hi] = std::minmax_element(v.begin(), v.end());
  const double a = *lo, span = *hi - *lo;
  for (double& x : v) x = span > 0.0 ? (x - a) / span : 0.0;
}

void check(const TerrainParams& p) {
  const ParamChecks c("terrain", "terrain");
  c.in_range("nx", p.nx, 2, 8193);
  c.in_range("ny", p.ny, 2, 8193);
  c.above("spacing", p.spacing, 0.0, 10000.0);
  c.in_range("relief", p.relief, 0.0, 20000.0);
  c.in_range("base", p.base, -20000.0, 20000.0);
  c.above("roughness", p.roughness, 0.0, 0.999);
  c.in_range("steps", p.steps, 2, 1000);
  c.in_range("holes", p.holes, 0.0, 0.5);
  if (p.style != "fractal" && p.style != "ridged" && p.style != "terraces" && p.style != "flat")
    c.fail("style", "'" + p.style + "' is none of fractal, ridged, terraces, flat");
}

}  // namespace

TerrainParams thesis_terrain_params() {
  TerrainParams p;
  p.nx = 1711, p.ny = 1451, p.spacing = 38.6;  // 66.0 km x 56.0 km, 4,959,000 triangles
  p.relief = 1500.0;
  return p;
}

Terrain generate_terrain(const TerrainParams& p, std::uint64_t seed) {
  check(p);
  Terrain t;
  t.nx = std::uint32_t(p.nx), t.ny = std::uint32_t(p.ny);
  t.dx = t.dy = p.spacing;
  t.corner = {-0.5 * (t.nx - 1) * t.dx, -0.5 * (t.ny - 1) * t.dy};
  t.source = "generated " + p.style + " terrain, seed " + std::to_string(seed) + ", " + terrain_params_to_json(p).dump();
  t.z.assign(t.vertex_count(), p.base);
  if (p.holes > 0.0) {
    t.hole.assign(t.vertex_count(), 0);
    for (std::uint32_t j = 0; j < t.ny; ++j)
      for (std::uint32_t i = 0; i < t.nx; ++i) t.hole[t.index(i, j)] = Random::stream(seed, kHoleTag, i, j).bernoulli(p.holes);
    if (std::all_of(t.hole.begin(), t.hole.end(), [](std::uint8_t h) { return h != 0; })) t.hole[0] = 0;
  }
  if (p.style == "flat") return t;
  std::size_t n = 2;
  while (n + 1 < std::size_t(std::max(p.nx, p.ny))) n *= 2;
  const std::vector<double> field = diamond_square(n + 1, p.roughness, seed);
  std::vector<double> u(t.vertex_count());
  for (std::uint32_t j = 0; j < t.ny; ++j)
    for (std::uint32_t i = 0; i < t.nx; ++i) u[t.index(i, j)] = field[j * (n + 1) + i];
  normalise(u);
  if (p.style == "ridged") {
    for (double& x : u) x = (1.0 - std::abs(2.0 * x - 1.0)) * (1.0 - std::abs(2.0 * x - 1.0));
    normalise(u);
  } else if (p.style == "terraces") {
    for (double& x : u) x = std::min(std::floor(x * p.steps), double(p.steps - 1)) / (p.steps - 1);
  }
  for (std::size_t v = 0; v < u.size(); ++v) t.z[v] = p.base + p.relief * u[v];
  return t;
}

TerrainParams terrain_params_from_json(const nlohmann::json& params) {
  TerrainParams p;
  nlohmann::json rest = params.is_null() ? nlohmann::json::object() : params;
  if (rest.is_object() && rest.contains("preset")) {
    const nlohmann::json& preset = rest["preset"];
    if (preset == "thesis")
      p = thesis_terrain_params();
    else if (preset != "default")
      throw InputError("terrain", "preset", "terrain: must be \"default\" or \"thesis\" (got " + preset.dump() + ")");
    rest.erase("preset");
  }
  overlay_params_json(p, rest, "terrain", "terrain");
  check(p);
  return p;
}

nlohmann::json terrain_params_to_json(const TerrainParams& params) { return params_to_json(params); }

}  // namespace cullcheck::generators
