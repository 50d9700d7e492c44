// Google Benchmark drivers (issue: OH(OS) along the street walk on the 160,000-building city,
// and generation time). Each benchmark repeats five times and reports the median; compare
// methods as ratios of medians from one run, never across runs or machines.
//
//   build/reports/benchmarks/bench_culling --benchmark_format=json > bench.json
#include <benchmark/benchmark.h>

#include <nlohmann/json.hpp>

#include "engine/method.hpp"
#include "engine/spatial/quadtree.hpp"
#include "generators/camera_paths.hpp"
#include "generators/city.hpp"

namespace cullcheck {
namespace {

// The thesis testbed (ch. 3.2): 400 x 400 buildings of 46 triangles.
const Scene& thesis_scene() {
  static const Scene scene = generators::make_city("thesis", 1, nlohmann::json::object());
  return scene;
}

// A 1,000-frame pedestrian walk through its streets (30 frames/s, 1.4 m/s, turns, sidesteps).
const CameraPath& thesis_walk() {
  static const CameraPath path = generators::make_camera_path("street_walk", thesis_scene(), 1, {{"frames", 1000}});
  return path;
}

void BM_GenerateThesisCity(benchmark::State& state) {
  for (auto _ : state) {
    Scene scene = generators::make_city("thesis", 1, nlohmann::json::object());
    benchmark::DoNotOptimize(scene.buildings.data());
  }
  state.counters["buildings"] = 160000;
}
BENCHMARK(BM_GenerateThesisCity)->Unit(benchmark::kMillisecond)->Repetitions(5)->ReportAggregatesOnly(true);

void BM_GenerateDefaultCity(benchmark::State& state) {
  for (auto _ : state) {
    Scene scene = generators::make_city("default", 1, nlohmann::json::object());
    benchmark::DoNotOptimize(scene.buildings.data());
  }
}
BENCHMARK(BM_GenerateDefaultCity)->Unit(benchmark::kMillisecond)->Repetitions(5)->ReportAggregatesOnly(true);

void BM_BuildQuadtreeThesisCity(benchmark::State& state) {
  const Scene& scene = thesis_scene();
  for (auto _ : state) {
    Quadtree tree(scene, 8);
    benchmark::DoNotOptimize(tree.cells().data());
  }
}
BENCHMARK(BM_BuildQuadtreeThesisCity)->Unit(benchmark::kMillisecond)->Repetitions(5)->ReportAggregatesOnly(true);

// One iteration culls one frame of the walk, cycling through it; time per iteration is the
// culling time per frame.
void BM_CullThesisStreetWalk(benchmark::State& state, const std::string& method_name) {
  const Scene& scene = thesis_scene();
  const CameraPath& path = thesis_walk();
  auto method = make_method(method_name, scene);
  std::size_t frame = 0;
  double pvs = 0, cells = 0, nodes = 0, frames = 0;
  for (auto _ : state) {
    const CullResult r = method->cull(path.frames[frame]);
    benchmark::DoNotOptimize(r.pvs.data());
    pvs += static_cast<double>(r.pvs.size());
    cells += static_cast<double>(r.stats.cells_tested);
    nodes += static_cast<double>(r.stats.horizon_nodes);
    frames += 1;
    frame = (frame + 1) % path.frames.size();
  }
  state.counters["pvs_per_frame"] = pvs / frames;
  state.counters["cells_tested_per_frame"] = cells / frames;
  state.counters["horizon_nodes_per_frame"] = nodes / frames;
}
BENCHMARK_CAPTURE(BM_CullThesisStreetWalk, frustum, std::string("frustum"))
    ->Unit(benchmark::kMicrosecond)->MinTime(1.0)->Repetitions(5)->ReportAggregatesOnly(true);
BENCHMARK_CAPTURE(BM_CullThesisStreetWalk, oh_os_conservative, std::string("oh_os_conservative"))
    ->Unit(benchmark::kMicrosecond)->MinTime(1.0)->Repetitions(5)->ReportAggregatesOnly(true);
BENCHMARK_CAPTURE(BM_CullThesisStreetWalk, oh_os_thesis, std::string("oh_os_thesis"))
    ->Unit(benchmark::kMicrosecond)->MinTime(1.0)->Repetitions(5)->ReportAggregatesOnly(true);

}  // namespace
}  // namespace cullcheck

BENCHMARK_MAIN();
