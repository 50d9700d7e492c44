// Oracle throughput next to bare Embree on the same rays (design: the oracle must run millions
// of rays per second). Counters: oracle_rays_per_s (the whole query: sample generation, casting,
// merging) and bare_embree_rays_per_s (the same rays re-cast in a bare rtcIntersect1 loop on as
// many threads).
#include <benchmark/benchmark.h>

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

}  // namespace
}  // namespace cullcheck::oracle

BENCHMARK_MAIN();
