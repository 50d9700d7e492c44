// Google Benchmark drivers for the mesh scene files a subject is handed (core/formats/): writing
// the thesis testbed's .glb and reading it back, at 100 x 100 and 400 x 400 buildings (the gate
// writes one per run unless --no-glb). These were timings printed by formats_test; a time is a
// benchmark's to measure, not a test's.
//
//   build/reports/benchmarks/bench_formats
#include <benchmark/benchmark.h>

#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <unistd.h>

#include "core/formats/mesh_formats.hpp"
#include "generators/city.hpp"

namespace cullcheck {
namespace {

const Scene& thesis_scene(int grid) {
  static std::map<int, Scene> scenes;
  auto [it, added] = scenes.try_emplace(grid);
  if (added) it->second = generators::make_city("thesis", 1, {{"grid_x", grid}, {"grid_y", grid}});
  return it->second;
}

std::string scratch_glb(int grid) {
  return (std::filesystem::temp_directory_path() /
          ("cullcheck_bench_thesis_" + std::to_string(grid) + "_" + std::to_string(::getpid()) + ".glb"))
      .string();
}

// Arg: grid side (buildings = grid x grid, 46 triangles each).
void BM_WriteGlbThesisCity(benchmark::State& state) {
  const int grid = int(state.range(0));
  const Scene& scene = thesis_scene(grid);
  const std::string path = scratch_glb(grid);
  for (auto _ : state) formats::write_glb(scene, path);
  state.counters["buildings"] = double(scene.buildings.size());
  state.counters["bytes"] = double(std::filesystem::file_size(path));
  std::filesystem::remove(path);
}
BENCHMARK(BM_WriteGlbThesisCity)->Arg(100)->Arg(400)->Unit(benchmark::kMillisecond);

void BM_ReadGltfThesisCity(benchmark::State& state) {
  const int grid = int(state.range(0));
  const Scene& scene = thesis_scene(grid);
  const std::string path = scratch_glb(grid);
  formats::write_glb(scene, path);
  std::size_t objects = 0;
  for (auto _ : state) {
    const Scene back = formats::read_gltf(path);
    objects = back.buildings.size() + back.meshes.size();
  }
  state.counters["objects"] = double(objects);
  std::filesystem::remove(path);
}
BENCHMARK(BM_ReadGltfThesisCity)->Arg(100)->Arg(400)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace cullcheck

BENCHMARK_MAIN();
