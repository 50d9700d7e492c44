// Google Benchmark drivers: generation time; view-cell PVSs (issue 4); VbAoI nodes and simulations
// (issue 5); thesis Table 3.2 (OH(IS), OH(OS), ΔH culling time
// along a 1,000-frame street walk on the 160,000-building city); and how each method's cost grows
// with the city (10k, 40k, 160k, 640k buildings). Each benchmark repeats five times and reports
// the median; compare methods as ratios of medians from one run, never across runs or machines.
// ΔH methods keep state from frame to frame, so one iteration is the next frame of the walk.
//
//   build/reports/benchmarks/bench_culling --benchmark_format=json > bench.json
#include <benchmark/benchmark.h>

#include <map>
#include <memory>
#include <nlohmann/json.hpp>

#include "engine/frustum/range_detection.hpp"
#include "engine/method.hpp"
#include "engine/spatial/quadtree.hpp"
#include "generators/camera_paths.hpp"
#include "generators/city.hpp"
#include "generators/street_cells.hpp"
#include "engine/shrinking/view_cell.hpp"
#include "engine/vbaoi/navigation_graph.hpp"
#include "engine/vbaoi/sight_filter.hpp"
#include "engine/vbaoi/simulation.hpp"
#include "generators/navigable_regions.hpp"

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
  double pvs = 0, cells = 0, nodes = 0, fires = 0, frames = 0;
  for (auto _ : state) {
    const CullResult r = method->cull(path.frames[frame]);
    benchmark::DoNotOptimize(r.pvs.data());
    pvs += static_cast<double>(r.pvs.size());
    cells += static_cast<double>(r.stats.cells_tested);
    nodes += static_cast<double>(r.stats.horizon_nodes);
    fires += static_cast<double>(r.stats.guard_fires);
    frames += 1;
    frame = (frame + 1) % path.frames.size();
  }
  state.counters["pvs_per_frame"] = pvs / frames;
  state.counters["cells_tested_per_frame"] = cells / frames;
  state.counters["horizon_nodes_per_frame"] = nodes / frames;
  state.counters["guard_fires_per_frame"] = fires / frames;
}
BENCHMARK_CAPTURE(BM_CullThesisStreetWalk, oh_is, std::string("oh_is"))
    ->Unit(benchmark::kMicrosecond)->MinTime(1.0)->Repetitions(5)->ReportAggregatesOnly(true);
BENCHMARK_CAPTURE(BM_CullThesisStreetWalk, frustum, std::string("frustum"))
    ->Unit(benchmark::kMicrosecond)->MinTime(1.0)->Repetitions(5)->ReportAggregatesOnly(true);
BENCHMARK_CAPTURE(BM_CullThesisStreetWalk, oh_os_conservative, std::string("oh_os_conservative"))
    ->Unit(benchmark::kMicrosecond)->MinTime(1.0)->Repetitions(5)->ReportAggregatesOnly(true);
BENCHMARK_CAPTURE(BM_CullThesisStreetWalk, oh_os_thesis, std::string("oh_os_thesis"))
    ->Unit(benchmark::kMicrosecond)->MinTime(1.0)->Repetitions(5)->ReportAggregatesOnly(true);
BENCHMARK_CAPTURE(BM_CullThesisStreetWalk, delta_h_thesis, std::string("delta_h_thesis"))
    ->Unit(benchmark::kMicrosecond)->MinTime(1.0)->Repetitions(5)->ReportAggregatesOnly(true);
BENCHMARK_CAPTURE(BM_CullThesisStreetWalk, delta_h_guarded, std::string("delta_h_guarded"))
    ->Unit(benchmark::kMicrosecond)->MinTime(1.0)->Repetitions(5)->ReportAggregatesOnly(true);

// The guarded ΔH's motion region against its cost: radius in centimetres (10, the default, to 200).
// Small regions decide more buildings without a test but re-anchor (the guard fires) more often.
// Frames here follow each other with nothing in between, so at small radii the frame that needs
// the next region waits for the second thread to finish it: wall time ("Time") then exceeds the
// calling thread's CPU time ("CPU"), which is the frame's own work. background_ms_per_frame is
// the second thread's (CullStatistics::background_ms).
void BM_GuardedDeltaRadius(benchmark::State& state) {
  const Scene& scene = thesis_scene();
  const CameraPath& path = thesis_walk();
  MethodOptions options;
  options.delta_radius = static_cast<double>(state.range(0)) / 100.0;
  auto method = make_method("delta_h_guarded", scene, options);
  std::size_t frame = 0;
  double fires = 0, frames = 0, background = 0;
  for (auto _ : state) {
    const CullResult r = method->cull(path.frames[frame]);
    benchmark::DoNotOptimize(r.pvs.data());
    fires += static_cast<double>(r.stats.guard_fires);
    background += r.stats.background_ms;
    frames += 1;
    frame = (frame + 1) % path.frames.size();
  }
  state.counters["guard_fires_per_frame"] = fires / frames;
  state.counters["background_ms_per_frame"] = background / frames;
}
BENCHMARK(BM_GuardedDeltaRadius)->Arg(10)->Arg(25)->Arg(50)->Arg(100)->Arg(200)->Unit(benchmark::kMicrosecond)->MinTime(1.0)
    ->Repetitions(5)->ReportAggregatesOnly(true);

// Cost against city size: the thesis layout with grid x grid buildings (100: 10k, 200: 40k,
// 400: 160k, 800: 640k) and a 1,000-frame street walk through it; one iteration culls one frame.
struct SizedCity {
  Scene scene;
  CameraPath walk;
};
const SizedCity& sized_city(int grid) {
  static std::map<int, std::unique_ptr<SizedCity>> cities;
  auto& c = cities[grid];
  if (!c) {
    c = std::make_unique<SizedCity>();
    c->scene = generators::make_city("thesis", 1, {{"grid_x", grid}, {"grid_y", grid}});
    c->walk = generators::make_camera_path("street_walk", c->scene, 1, {{"frames", 1000}});
  }
  return *c;
}

void BM_CullByCitySize(benchmark::State& state, const std::string& method_name) {
  const SizedCity& city = sized_city(static_cast<int>(state.range(0)));
  auto method = make_method(method_name, city.scene);
  std::size_t frame = 0;
  double cells = 0, nodes = 0, frames = 0;
  for (auto _ : state) {
    const CullResult r = method->cull(city.walk.frames[frame]);
    benchmark::DoNotOptimize(r.pvs.data());
    cells += static_cast<double>(r.stats.cells_tested);
    nodes += static_cast<double>(r.stats.horizon_nodes);
    frames += 1;
    frame = (frame + 1) % city.walk.frames.size();
  }
  state.counters["buildings"] = static_cast<double>(city.scene.buildings.size());
  state.counters["cells_tested_per_frame"] = cells / frames;
  state.counters["horizon_nodes_per_frame"] = nodes / frames;
}
#define CULLCHECK_SIZE_BENCH(method)                                                             \
  BENCHMARK_CAPTURE(BM_CullByCitySize, method, std::string(#method))                             \
      ->Arg(100)->Arg(200)->Arg(400)->Arg(800)->Unit(benchmark::kMicrosecond)->MinTime(0.5)       \
      ->Repetitions(3)->ReportAggregatesOnly(true)
CULLCHECK_SIZE_BENCH(frustum);
CULLCHECK_SIZE_BENCH(oh_is);
CULLCHECK_SIZE_BENCH(oh_os_conservative);
CULLCHECK_SIZE_BENCH(delta_h_guarded);

// Frustum culling by planes and by ranges (Sunar et al.'s RDT as published and corrected,
// Placeres's radar approach) along a 1,000-frame street walk of the default city (arg 0) and of
// the 160,000-building city (arg 1): time per frame, bound tests per tested object (a box against
// the six planes counts one; RDT's front, sphere and corner tests one each) and PVS size.
const SizedCity& frustum_city(int which) {
  static std::map<int, std::unique_ptr<SizedCity>> cities;
  auto& c = cities[which];
  if (!c) {
    c = std::make_unique<SizedCity>();
    c->scene = generators::make_city(which == 0 ? "default" : "thesis", 1, nlohmann::json::object());
    c->walk = generators::make_camera_path("street_walk", c->scene, 1, {{"frames", 1000}});
  }
  return *c;
}

void BM_FrustumWalk(benchmark::State& state, const std::string& method_name) {
  const SizedCity& city = frustum_city(static_cast<int>(state.range(0)));
  auto method = make_method(method_name, city.scene);
  std::size_t frame = 0;
  double pvs = 0, tests = 0, objects = 0, frames = 0;
  for (auto _ : state) {
    const CullResult r = method->cull(city.walk.frames[frame]);
    benchmark::DoNotOptimize(r.pvs.data());
    pvs += static_cast<double>(r.pvs.size());
    tests += static_cast<double>(r.stats.bound_tests);
    objects += static_cast<double>(r.stats.cells_tested + r.stats.buildings_tested);
    frames += 1;
    frame = (frame + 1) % city.walk.frames.size();
  }
  state.counters["buildings"] = static_cast<double>(city.scene.buildings.size());
  state.counters["pvs_per_frame"] = pvs / frames;
  state.counters["objects_tested_per_frame"] = objects / frames;
  state.counters["bound_tests_per_object"] = objects > 0 ? tests / objects : 0.0;
}
#define CULLCHECK_FRUSTUM_BENCH(method)                                                                     \
  BENCHMARK_CAPTURE(BM_FrustumWalk, method, std::string(#method))->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond) \
      ->MinTime(0.5)->Repetitions(5)->ReportAggregatesOnly(true)
CULLCHECK_FRUSTUM_BENCH(frustum);
CULLCHECK_FRUSTUM_BENCH(rdt);
CULLCHECK_FRUSTUM_BENCH(rdt_corrected);
CULLCHECK_FRUSTUM_BENCH(radar_frustum);

// The paper's own comparison, without a hierarchy: every building's box tested at every frame
// of the same walks (arg 0: the default city, 1: the 160,000-building city), one iteration one
// frame; the second arg picks the test: 0 the six planes, 1 RDT as published, 2 corrected, 3 the
// radar approach. Time per object is the iteration time over `buildings`.
void BM_FrustumObjectTest(benchmark::State& state) {
  const SizedCity& city = frustum_city(static_cast<int>(state.range(0)));
  const int which = static_cast<int>(state.range(1));
  const RangeRule rules[] = {RangeRule::published, RangeRule::corrected, RangeRule::radar};
  std::vector<double> radius;  // kept with each object, as the paper does
  for (const Building& b : city.scene.buildings) radius.push_back(0.5 * length(b.bounds.hi - b.bounds.lo));
  std::size_t frame = 0;
  double kept = 0, frames = 0;
  std::uint64_t tests = 0;
  for (auto _ : state) {
    const Camera& camera = city.walk.frames[frame];
    std::uint64_t in = 0;
    if (which == 0) {
      const ViewVolume volume(camera);
      for (const Building& b : city.scene.buildings) in += volume.may_intersect(b.bounds);
    } else {
      const CameraRanges ranges(camera);
      for (std::size_t i = 0; i < radius.size(); ++i)
        in += !range_outside(rules[which - 1], ranges, city.scene.buildings[i].bounds, radius[i], tests);
    }
    benchmark::DoNotOptimize(in);
    kept += static_cast<double>(in);
    frames += 1;
    frame = (frame + 1) % city.walk.frames.size();
  }
  const double n = static_cast<double>(city.scene.buildings.size());
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * city.scene.buildings.size()));
  state.counters["buildings"] = n;
  state.counters["kept_per_frame"] = kept / frames;
  state.counters["tests_per_object"] = which == 0 ? 1.0 : static_cast<double>(tests) / (frames * n);
}
BENCHMARK(BM_FrustumObjectTest)->ArgsProduct({{0, 1}, {0, 1, 2, 3}})->Unit(benchmark::kMicrosecond)->MinTime(0.5)->Repetitions(5)
    ->ReportAggregatesOnly(true);


// From-region PVS of view cells (issue 4): the default city's street cells k * 37, boundary
// samples 2ε apart (ε = √2 m), each region method with and without decisions carried between
// neighbouring samples (arg 1 / 0). One iteration computes one cell.
void BM_ViewCell(benchmark::State& state, const std::string& method_name) {
  static const Scene scene = generators::make_city("default", 1, nlohmann::json::object());
  static const std::vector<generators::NavigableRegion> cells = *generators::street_cells_of(scene);
  auto method = make_region_method(method_name, scene);
  ViewCellPvs cells_pvs(*method, scene);
  const bool carry = state.range(0) != 0;
  std::size_t next = 0;
  double pvs = 0, cells_done = 0;
  for (auto _ : state) {
    const ViewCell cell{cells[(next++ * 37) % cells.size()].ring, 1.7};
    const ViewCellResult r = cells_pvs.compute(cell, 1.4142135623730951, CellSampling::boundary, carry);
    pvs += static_cast<double>(r.pvs.size());
    ++cells_done;
  }
  state.counters["pvs_per_cell"] = pvs / cells_done;
}
#define CULLCHECK_CELL_BENCH(method)                                                             \
  BENCHMARK_CAPTURE(BM_ViewCell, method, std::string(#method))                                   \
      ->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->MinTime(1.0)->Repetitions(5)->ReportAggregatesOnly(true)
CULLCHECK_CELL_BENCH(shrink_former);
CULLCHECK_CELL_BENCH(shrink_adjustable_thesis);
CULLCHECK_CELL_BENCH(shrink_adjustable_corrected);
CULLCHECK_CELL_BENCH(shrink_adjustable_conservative);
CULLCHECK_CELL_BENCH(shrink_minkowski);

// VbAoI (issue 5) on the default city: one node's PVSo and PVSn (view cell plus the navigable
// regions as passive targets; compare with BM_ViewCell/shrink_former/1 for what PVSn adds), and
// the simulation of 10, 100 and 1,000 clients for 5 simulated seconds without the oracle's line-
// of-sight checks (its own cost, from one graph built once). One iteration: one node / one run.
struct DefaultCityGraph {
  Scene scene = generators::make_city("default", 1, nlohmann::json::object());
  std::vector<NavigableRegion> regions = generators::navigable_regions(scene);
  NavigationGraph graph;
};
DefaultCityGraph& default_city_graph(bool with_graph) {
  static DefaultCityGraph g;
  if (with_graph && g.graph.nodes.empty()) {
    NavigationGraphOptions o;
    o.threads = 2;
    g.graph = build_navigation_graph(g.scene, g.regions, o);
  }
  return g;
}

void BM_VbaoiNode(benchmark::State& state) {
  const DefaultCityGraph& g = default_city_graph(false);
  NodeVisibility nodes(g.scene, g.regions, NavigationGraphOptions{});
  std::size_t next = 0;
  double pvs_o = 0, pvs_n = 0, done = 0;
  for (auto _ : state) {
    const ViewCellResult r = nodes.compute((next++ * 37) % g.regions.size());
    pvs_o += static_cast<double>(r.pvs.size());
    pvs_n += static_cast<double>(r.passive.size());
    ++done;
  }
  state.counters["pvs_o_per_node"] = pvs_o / done;
  state.counters["pvs_n_per_node"] = pvs_n / done;
}
BENCHMARK(BM_VbaoiNode)->Unit(benchmark::kMillisecond)->MinTime(1.0)->Repetitions(5)->ReportAggregatesOnly(true);

// The same on the main job's VbAoI city (report --vbaoi: a 41 x 41-block Manhattan grid, 10,086
// buildings, 5,208 nodes), whose whole graph issue 17 wants in 15 s on two cores: every 61st node
// in turn, with what a sample costs (tests, shadows and skipped buildings per sample).
void BM_VbaoiNodeMainCity(benchmark::State& state) {
  static const Scene scene =
      generators::make_city("manhattan", 1, nlohmann::json{{"blocks_x", 41}, {"blocks_y", 41}});
  static const std::vector<NavigableRegion> regions = generators::navigable_regions(scene);
  NavigationGraphOptions options;
  options.carry = state.range(0) != 0;
  NodeVisibility nodes(scene, regions, options);
  std::size_t next = 0;
  double samples = 0, pvs_o = 0, cells = 0, tested = 0, skipped = 0, shadows = 0, done = 0;
  for (auto _ : state) {
    const ViewCellResult r = nodes.compute((next++ * 61) % regions.size());
    samples += static_cast<double>(r.samples);
    pvs_o += static_cast<double>(r.pvs.size());
    cells += static_cast<double>(r.stats.cells_tested);
    tested += static_cast<double>(r.stats.buildings_tested);
    skipped += static_cast<double>(r.stats.items_skipped);
    shadows += static_cast<double>(r.stats.occluders_applied);
    ++done;
  }
  state.counters["samples_per_node"] = samples / done;
  state.counters["pvs_o_per_node"] = pvs_o / done;
  state.counters["cells_per_sample"] = cells / samples;
  state.counters["tested_per_sample"] = tested / samples;
  state.counters["skipped_per_sample"] = skipped / samples;
  state.counters["shadows_per_sample"] = shadows / samples;
}
BENCHMARK(BM_VbaoiNodeMainCity)->ArgName("carry")->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->MinTime(2.0)->Repetitions(3)->ReportAggregatesOnly(true);

void BM_VbaoiSimulation(benchmark::State& state) {
  const DefaultCityGraph& g = default_city_graph(true);
  vbaoi::SimulationOptions o;
  o.clients = static_cast<std::uint32_t>(state.range(0));
  o.duration = 5.0;
  double client_ticks = 0, messages = 0;
  for (auto _ : state) {
    const vbaoi::SimulationResult r = vbaoi::simulate(g.scene, g.graph, o, {});
    client_ticks += static_cast<double>(r.active_client_ticks);
    messages += static_cast<double>(r.policies[0].messages);
  }
  state.counters["client_ticks_per_second"] = benchmark::Counter(client_ticks, benchmark::Counter::kIsRate);
  state.counters["vbaoi_messages_per_run"] = messages / static_cast<double>(state.iterations());
}
BENCHMARK(BM_VbaoiSimulation)->Arg(10)->Arg(100)->Arg(1000)->Unit(benchmark::kMillisecond)->Repetitions(5)
    ->ReportAggregatesOnly(true);

// The VbAoI server's sight filter, one query per (sender, listener) pair as VbAoI's channels pair
// them: a sender at a random point of a node, a listener at a random point of a node in its PVSn,
// the disc a 2 m/s walker covers in one 10 Hz tick. Counters: queries a second, the share hidden
// (the deliveries the filter saves) and prisms tested a query.
void BM_VbaoiSightFilter(benchmark::State& state) {
  const DefaultCityGraph& g = default_city_graph(true);
  vbaoi::SightFilter filter(g.scene, g.graph.options.eye_height);
  Random rng(5);
  std::vector<std::pair<Vec2, Vec2>> pairs;
  for (int k = 0; k < 4096; ++k) {
    const NavigationNode& a = g.graph.nodes[static_cast<std::size_t>(rng.uniform_int(0, static_cast<std::int64_t>(g.graph.nodes.size()) - 1))];
    const NodeId b = a.pvs_n[static_cast<std::size_t>(rng.uniform_int(0, static_cast<std::int64_t>(a.pvs_n.size()) - 1))];
    pairs.push_back({random_point_in(a.coords, rng), random_point_in(g.graph.nodes[b].coords, rng)});
  }
  double queries = 0, hidden = 0;
  std::size_t next = 0;
  const std::uint64_t tested_before = filter.prisms_tested();
  for (auto _ : state) {
    const auto& [from, to] = pairs[next++ % pairs.size()];
    const bool h = filter.hidden(from, to, 0.2);
    benchmark::DoNotOptimize(h);
    hidden += h ? 1 : 0;
    ++queries;
  }
  state.counters["queries_per_second"] = benchmark::Counter(queries, benchmark::Counter::kIsRate);
  state.counters["hidden_share"] = hidden / queries;
  state.counters["prisms_per_query"] = static_cast<double>(filter.prisms_tested() - tested_before) / queries;
}
BENCHMARK(BM_VbaoiSightFilter)->Unit(benchmark::kMicrosecond)->Repetitions(3)->ReportAggregatesOnly(true);

}  // namespace
}  // namespace cullcheck

BENCHMARK_MAIN();
