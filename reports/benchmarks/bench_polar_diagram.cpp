// Polar diagrams (engine/polar_diagram/) against CGAL's exact visibility polygon
// (oracle/exact_2d.hpp): construction of the four diagrams, and one query per frame along a
// level street walk, on the default city and on a city like the paper's (600 star-shaped
// footprints, 45,000 vertices). Arguments: city (0 default, 1 paper-like), view in degrees.
// Counters: visible buildings (k), rays, rays per 2k.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <memory>
#include <vector>

#include "core/errors.hpp"
#include "engine/polar_diagram/polar_diagram.hpp"
#include "engine/polar_diagram/visibility_fan.hpp"
#include "generators/camera_paths.hpp"
#include "generators/city.hpp"
#include "generators/plan_scenes.hpp"
#include "oracle/exact_2d.hpp"

namespace cullcheck {
namespace {

struct City {
  Scene scene;
  std::vector<Vec2> vertices;
  std::vector<Camera> frames;  // level, eye outside every footprint
};

const City& city(int which) {
  static std::unique_ptr<City> cities[2];
  if (!cities[which]) {
    auto c = std::make_unique<City>();
    c->scene = which == 0 ? generators::default_city(1) : generators::star_block_city({}, 1);
    // Both sides use footprints alone; CGAL's refuses buildings not taller than the eye (the
    // default city's kiosks), so all are raised.
    for (Building& b : c->scene.buildings) b.height = std::max(b.height, 100.0);
    c->vertices = polar::footprint_vertices(c->scene);
    generators::StreetWalkParams walk;
    walk.frames = 300;
    const std::vector<Camera> frames =
        which == 0 ? generators::street_walk(c->scene, walk, 1).frames : generators::star_block_walk({}, walk.frames);
    const oracle::ExactVisibility2d exact(c->scene);
    for (Camera f : frames) {
      f.pitch = f.roll = 0.0;
      try {
        exact.visible(f);
        c->frames.push_back(f);
      } catch (const InputError&) {
      }
    }
    if (c->frames.empty()) throw std::logic_error("bench_polar_diagram: no frame of the walk is usable");
    cities[which] = std::move(c);
  }
  return *cities[which];
}

Camera with_view(Camera c, int degrees) {
  c.hfov = degrees >= 360 ? kTwoPi : degrees * kPi / 180;
  return c;
}

void BM_PolarDiagramsBuild(benchmark::State& state) {
  const City& c = city(static_cast<int>(state.range(0)));
  for (auto _ : state) {
    const polar::PolarDiagrams d(c.vertices);
    benchmark::DoNotOptimize(d.diagrams.data());
  }
  state.counters["vertices"] = static_cast<double>(c.vertices.size());
}
BENCHMARK(BM_PolarDiagramsBuild)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

void BM_PolarFanQuery(benchmark::State& state) {
  const City& c = city(static_cast<int>(state.range(0)));
  const polar::VisibilityFan fan(c.scene);
  std::size_t i = 0;
  double rays = 0, k = 0, queries = 0;
  for (auto _ : state) {
    const Camera cam = with_view(c.frames[i++ % c.frames.size()], static_cast<int>(state.range(1)));
    const polar::FanResult r = fan.visible(plan(cam.position), polar::plan_wedge(cam));
    rays += static_cast<double>(r.stats.rays), k += static_cast<double>(r.visible.size()), ++queries;
  }
  state.counters["k"] = k / queries;
  state.counters["rays"] = rays / queries;
  state.counters["rays_per_2k"] = k > 0 ? rays / (2 * k) : 0.0;
}
BENCHMARK(BM_PolarFanQuery)->ArgsProduct({{0, 1}, {90, 360}})->Unit(benchmark::kMicrosecond);

void BM_CgalVisibilityQuery(benchmark::State& state) {
  const City& c = city(static_cast<int>(state.range(0)));
  const oracle::ExactVisibility2d exact(c.scene);
  std::size_t i = 0;
  for (auto _ : state) {
    const Camera cam = with_view(c.frames[i++ % c.frames.size()], static_cast<int>(state.range(1)));
    benchmark::DoNotOptimize(exact.visible(cam).visible.data());
  }
}
BENCHMARK(BM_CgalVisibilityQuery)->ArgsProduct({{0, 1}, {90, 360}})->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace cullcheck

BENCHMARK_MAIN();
