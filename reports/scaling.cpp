#include "reports/scaling.hpp"

#include <sys/resource.h>

#include <cstdio>
#include <memory>

#include "engine/method.hpp"
#include "engine/spatial/traversal_bound.hpp"
#include "generators/camera_paths.hpp"
#include "generators/city.hpp"
#include "reports/statistics.hpp"
#include "reports/test_costs.hpp"

namespace cullcheck {
namespace {

// The process's resident-memory high-water mark so far (Linux reports ru_maxrss in KiB); 0 when
// the call fails.
std::uint64_t peak_resident_bytes() {
  rusage usage{};
  if (getrusage(RUSAGE_SELF, &usage) != 0 || usage.ru_maxrss < 0) return 0;
  return static_cast<std::uint64_t>(usage.ru_maxrss) * 1024u;
}

}  // namespace

nlohmann::json run_scaling(const ScalingOptions& options) {
  nlohmann::json rows = nlohmann::json::array();
  for (int grid : options.grids) {
    const Scene scene = generators::make_city("thesis", options.seed, {{"grid_x", grid}, {"grid_y", grid}});
    const CameraPath walk = generators::make_camera_path("street_walk", scene, options.seed, {{"frames", options.frames}});
    std::vector<std::unique_ptr<CullingMethod>> methods;
    for (const std::string& name : options.methods) methods.push_back(make_method(name, scene));
    struct Tally {
      std::vector<double> ms, pvs, background;
      CullStatistics totals;  // counts summed over frames
      std::size_t differs = 0;
    };
    std::vector<Tally> tally(methods.size());
    std::size_t reference = methods.size();
    for (std::size_t m = 0; m < methods.size(); ++m)
      if (options.methods[m] == "oh_os_conservative") reference = m;
    std::vector<CullResult> results(methods.size());
    std::vector<std::unique_ptr<ExactTraversal>> traversals(methods.size());
    for (const Camera& camera : walk.frames) {
      for (std::size_t m = 0; m < methods.size(); ++m) {
        results[m] = methods[m]->cull(camera);
        take_exact_traversal(*methods[m], scene, traversals[m], results[m]);  // after the query's own timing
        tally[m].ms.push_back(results[m].stats.cull_ms);
        tally[m].background.push_back(results[m].stats.background_ms);
        tally[m].pvs.push_back(static_cast<double>(results[m].pvs.size()));
        add_counts(tally[m].totals, results[m].stats);
      }
      if (reference < methods.size())
        for (std::size_t m = 0; m < methods.size(); ++m) tally[m].differs += results[m].pvs != results[reference].pvs;
    }
    const double frames = static_cast<double>(walk.frames.size());
    nlohmann::json row_methods = nlohmann::json::array();
    for (std::size_t m = 0; m < methods.size(); ++m) {
      const Tally& t = tally[m];
      nlohmann::json r = {{"method", options.methods[m]},
                          {"cull_ms_median", median(t.ms)},
                          {"cull_ms_p95", percentile(t.ms, 95)},
                          {"background_ms_mean", mean(t.background)},
                          {"pvs_mean", mean(t.pvs)},
                          {"cells_tested_mean", static_cast<double>(t.totals.cells_tested) / frames},
                          {"buildings_tested_mean", static_cast<double>(t.totals.buildings_tested) / frames},
                          {"horizon_nodes_mean", static_cast<double>(t.totals.horizon_nodes) / frames},
                          {"tests_over_exact_traversal", tests_over_exact_traversal(t.totals)},
                          {"ns_per_test", ns_per_test(t.totals, mean(t.ms) * frames)}};
      if (reference < methods.size()) {
        r["frames_pvs_differs_from_oh_os"] = t.differs;
        const double own = median(t.ms);
        r["oh_os_cull_ms_median_ratio"] = own > 0 ? median(tally[reference].ms) / own : 0.0;
      }
      row_methods.push_back(r);
    }
    // Sizes run smallest first and each frees its city before the next, so the largest size's
    // figure is its own peak (city, quadtree, every method's structures, the walk), and a
    // smaller size's is a bound that may be the run's earlier sections'.
    rows.push_back({{"grid", grid},
                    {"buildings", scene.buildings.size()},
                    {"frames", walk.frames.size()},
                    {"peak_rss_bytes", peak_resident_bytes()},
                    {"methods", row_methods}});
  }
  return rows;
}

std::string scaling_table(const nlohmann::json& rows) {
  std::string out;
  char line[256];
  std::snprintf(line, sizeof line, "%9s %-20s %9s %9s %9s %9s %12s %9s %11s %7s\n", "buildings", "method", "ms_med", "ms_p95",
                "pvs_mean", "cells", "oh_os/method", "pvs!=oh_os", "tests/exact", "ns/test");
  out += line;
  for (const auto& row : rows)
    for (const auto& m : row["methods"]) {
      const nlohmann::json& exact = m.value("tests_over_exact_traversal", nlohmann::json(nullptr));
      char over[32] = "-";
      if (exact.is_number()) std::snprintf(over, sizeof over, "%.3f", exact.get<double>());
      std::snprintf(line, sizeof line, "%9zu %-20s %9.3f %9.3f %9.1f %9.1f %12.2f %9zu %11s %7.0f\n", row["buildings"].get<std::size_t>(),
                    m["method"].get<std::string>().c_str(), m["cull_ms_median"].get<double>(), m["cull_ms_p95"].get<double>(),
                    m["pvs_mean"].get<double>(), m["cells_tested_mean"].get<double>(),
                    m.value("oh_os_cull_ms_median_ratio", 0.0), m.value("frames_pvs_differs_from_oh_os", std::size_t{0}), over,
                    m.value("ns_per_test", 0.0));
      out += line;
    }
  for (const auto& row : rows) {
    std::snprintf(line, sizeof line, "%9zu buildings: peak resident memory %.0f MB (process high-water mark)\n",
                  row["buildings"].get<std::size_t>(),
                  static_cast<double>(row.value("peak_rss_bytes", std::uint64_t{0})) / (1024.0 * 1024.0));
    out += line;
  }
  return out;
}

}  // namespace cullcheck
