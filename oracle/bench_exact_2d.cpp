// The exact 2D oracle's cost (CGAL plan-view visibility; exact_2d.hpp): building its structure
// for a 500-building city and one 360-degree query, and a query alone on the built structure.
// This replaces the time limit Exact2d's test used to assert (oracle/tests/exact_2d_test.cpp).
#include <benchmark/benchmark.h>

#include "oracle/exact_2d.hpp"
#include "oracle/tests/test_scenes.hpp"

namespace cullcheck::oracle {
namespace {

void BM_Exact2dFiveHundredBuildings(benchmark::State& state) {
  const Scene scene = testing::jittered_grid_500();
  const Camera eye = testing::omni_camera(testing::kJitteredGridEye);
  std::size_t visible = 0;
  for (auto _ : state) {
    const ExactVisibility2d exact(scene);
    const Exact2dResult r = exact.visible(eye);
    visible = r.visible.size();
    benchmark::DoNotOptimize(r.visible.data());
  }
  state.counters["buildings"] = double(scene.buildings.size());
  state.counters["visible"] = double(visible);
  state.SetLabel("build + one query");
}
BENCHMARK(BM_Exact2dFiveHundredBuildings)->Unit(benchmark::kMillisecond);

void BM_Exact2dQueryFiveHundredBuildings(benchmark::State& state) {
  const Scene scene = testing::jittered_grid_500();
  const Camera eye = testing::omni_camera(testing::kJitteredGridEye);
  const ExactVisibility2d exact(scene);
  for (auto _ : state) {
    const Exact2dResult r = exact.visible(eye);
    benchmark::DoNotOptimize(r.visible.data());
  }
}
BENCHMARK(BM_Exact2dQueryFiveHundredBuildings)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace cullcheck::oracle
