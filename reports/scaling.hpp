// How culling cost grows with the city (issue: Table 3.2's ratios at 10k, 40k, 160k and 640k
// buildings). For each size, the thesis testbed layout with grid x grid buildings and a street
// walk through it; every method culls every frame in the same run, and each method's cost is
// reported next to its ratio to full OH(OS) at that size. No oracle here: the methods' accuracy
// is the path report's business; PVS identity with OH(OS) is counted per frame.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace cullcheck {

struct ScalingOptions {
  std::vector<int> grids = {100, 200, 400, 800};  // grid x grid buildings
  int frames = 1000;
  std::uint64_t seed = 1;
  std::vector<std::string> methods = {"frustum", "oh_is", "oh_os_conservative", "delta_h_thesis", "delta_h_guarded"};
};

// One row per city size: {"grid", "buildings", "frames", "methods": [{method, cull_ms_median,
// cull_ms_p95, background_ms_mean (work done ahead on another thread, not in cull_ms: the guarded
// ΔH's prefetch), pvs_mean, cells_tested_mean, buildings_tested_mean, horizon_nodes_mean,
// tests_over_exact_traversal (methods that sweep a quadtree, else null), ns_per_test,
// frames_pvs_differs_from_oh_os, oh_os_cull_ms_median_ratio}]}.
nlohmann::json run_scaling(const ScalingOptions& options);
// The rows above as a printed table.
std::string scaling_table(const nlohmann::json& rows);

}  // namespace cullcheck
