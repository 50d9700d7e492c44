// Oracle throughput next to bare Embree on the same rays (design: the oracle must run millions
// of rays per second). Counters: oracle_rays_per_s (the whole query: sample generation, casting,
// merging) and bare_embree_rays_per_s (the same rays re-cast in a bare rtcIntersect1 loop on as
// many threads). The pixel oracle's primary rays: pixel_rays_per_s, on the CLI's default city from
// a street-level camera (the first frame of its street walk) at 320 x 240.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <nlohmann/json.hpp>

#include "generators/camera_paths.hpp"
#include "generators/city.hpp"
#include "oracle/pixel_oracle.hpp"
#include "oracle/ray_oracle.hpp"
#include "oracle/tests/test_scenes.hpp"

namespace cullcheck::oracle {
namespace {

// Args: city seed (seed % 3 picks perspective or omnidirectional, see random_city), threads.
void BM_OracleWitness(benchmark::State& state) {
  const testing::RandomCity city = testing::random_city(std::uint64_t(state.range(0)));
  const RayOracle oracle(city.scene);
  SamplingOptions options;
  options.threads = int(state.range(1));
  std::uint64_t rays = 0;
  for (auto _ : state) {
    const OracleResult r = oracle.witness(city.camera, options);
    rays += r.rays_cast;
    benchmark::DoNotOptimize(r.witnessed.data());
  }
  RayLog log;
  const OracleResult once = oracle.witness(city.camera, options, &log);
  state.counters["rays_per_query"] = double(once.rays_cast);
  state.counters["buildings"] = double(city.scene.buildings.size());
  state.counters["witnessed"] = double(once.witnessed.size());
  state.counters["oracle_rays_per_s"] = benchmark::Counter(double(rays), benchmark::Counter::kIsRate);
  state.counters["bare_embree_rays_per_s"] = oracle.bare_embree_rays_per_second(log, options.threads, 0.3);
  state.SetLabel(city.kind);
}
BENCHMARK(BM_OracleWitness)->Args({3, 1})->Args({3, 2})->Args({5, 1})->Args({5, 2})->Unit(benchmark::kMillisecond)->UseRealTime();

// Args: threads; 0 = the full render, 1 = the full render and a comparison with a PVS holding
// every other object (the PVS-only rays where a culled object shows).
void BM_PixelOracleDefaultCity(benchmark::State& state) {
  static const Scene scene = generators::make_city("default", 1, nlohmann::json::object());
  static const RayOracle oracle(scene);
  const PixelOracle pixels(oracle);
  Camera camera = generators::street_walk(scene, {}, 1).frames.front();
  camera.width = 320, camera.height = 240;
  const int threads = int(state.range(0));
  const bool compare = state.range(1) != 0;
  std::vector<ObjectId> pvs = scene.ids();
  pvs.erase(std::remove_if(pvs.begin(), pvs.end(), [](ObjectId id) { return id % 2 == 1; }), pvs.end());
  std::uint64_t rays = 0;
  for (auto _ : state) {
    const IdImage full = pixels.render(camera, nullptr, threads);
    rays += full.ids.size();
    if (compare) {
      const PixelComparison c = pixels.compare(full, camera, pvs, threads);
      rays += c.misdrawn_pixels + c.witnesses.size();
      benchmark::DoNotOptimize(c.misdrawn_pixels);
    }
    benchmark::DoNotOptimize(full.ids.data());
  }
  state.counters["buildings"] = double(scene.buildings.size());
  state.counters["pixel_rays_per_s"] = benchmark::Counter(double(rays), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_PixelOracleDefaultCity)->Args({1, 0})->Args({2, 0})->Args({2, 1})->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
}  // namespace cullcheck::oracle

BENCHMARK_MAIN();
