// A sweeping method's tests against the fewest an exact traversal of its quadtree needs for the
// same PVS (engine/spatial/traversal_bound.hpp), and what a test costs: issue 17's bound for
// OH(OS), in the report's method rows and in the scaling rows.
#pragma once

#include <memory>

#include <nlohmann/json.hpp>

#include "engine/method.hpp"
#include "engine/spatial/traversal_bound.hpp"

namespace cullcheck {

// For a method that sweeps a quadtree, sets `result.stats.exact_traversal_tests` to the bound for
// its PVS; call it after the query, outside its timing. `counter` lives across frames and is
// rebuilt when the method's quadtree changes (a scene timeline's new frame).
inline void take_exact_traversal(const CullingMethod& method, const Scene& scene, std::unique_ptr<ExactTraversal>& counter,
                                 CullResult& result) {
  const Quadtree* quadtree = method.swept_quadtree();
  if (!quadtree) return;
  if (!counter || &counter->quadtree() != quadtree) counter = std::make_unique<ExactTraversal>(*quadtree, scene);
  result.stats.exact_traversal_tests = counter->tests_for(result.pvs).total();
}

inline std::uint64_t tests_made(const CullStatistics& totals) { return totals.cells_tested + totals.buildings_tested; }

// (cells + buildings tested) / exact traversal's tests, summed over frames; null when the method
// sweeps no quadtree (the bound was not taken).
inline nlohmann::json tests_over_exact_traversal(const CullStatistics& totals) {
  if (totals.exact_traversal_tests == 0) return nullptr;
  return static_cast<double>(tests_made(totals)) / static_cast<double>(totals.exact_traversal_tests);
}

// Nanoseconds of query time per test made (cells and buildings), over every frame; 0 without tests.
inline double ns_per_test(const CullStatistics& totals, double total_ms) {
  const std::uint64_t tests = tests_made(totals);
  return tests > 0 ? total_ms * 1e6 / static_cast<double>(tests) : 0.0;
}

}  // namespace cullcheck
