// Issue 17's speed and traffic targets read off a report.json: for each target the report has a
// figure for, the figure, the goal, whether it is met, and where in report.json it comes from;
// given a baseline report (the same command run on an earlier build), its figure too, so that
// one table says before and after. Every figure is derived from fields the report already holds
// (scaling, table_4_1, oracle, vbaoi); a target whose section the report lacks has no row.
//
// Rows (ids):
//   delta_h_guarded_median_speedup, delta_h_guarded_p95_speedup, delta_h_guarded_pvs_differs:
//     OH(OS)'s median (p95) cull time over the guarded ΔH's on the scaling walk of the city
//     nearest 160,000 buildings, at least 10 (3); frames whose PVS differs, 0.
//   adjustable_increase_<method>: Table 4.1 at 60 degrees, each adjustable-shrinking method's PVS
//     over the point PVS, at most +15% with 0 violations.
//   oracle_vs_bare_packets: the oracle's rays per second over the bare packet loop's on the same
//     rays in the same run, at least 0.9.
//   vbaoi_graph_seconds: the VbAoI graph's build time, under 15 s (the goal is set for the
//     10,086-building city; `from` names the city's size).
//   vbaoi_deliveries_vs_limit, vbaoi_missed_updates: VbAoI's deliveries over the physical limit at
//     the most clients run, at most 2, with 0 misses.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

namespace cullcheck {

// {"rows": [{"id", "goal" (text), "figure", "met", "from", ["before"]}], ["baseline": note]}.
nlohmann::json speed_targets(const nlohmann::json& report, const nlohmann::json* baseline = nullptr);
// The rows as a text table, one line each.
std::string speed_targets_text(const nlohmann::json& targets);

}  // namespace cullcheck
