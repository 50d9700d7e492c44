// VbAoI (issue 5, thesis ch. 5): the navigable-region graph of a city and the multi-client
// simulation, held to the oracle (line of sight between avatar eyes, Embree), for several client
// counts, with broadcast and circular areas of interest on the same runs. Writes report.json's
// "vbaoi" section and a text table.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/navigable_region.hpp"
#include "core/scene.hpp"
#include "engine/vbaoi/navigation_graph.hpp"
#include "engine/vbaoi/simulation.hpp"
#include "generators/navigable_regions.hpp"
#include "reports/claims.hpp"
#include "reports/scene_source.hpp"

namespace cullcheck {

struct VbaoiOptions {
  generators::FreeSpaceOptions regions;  // for scenes without street cells (generators/navigable_regions.hpp)
  NavigationGraphOptions graph;
  std::vector<std::uint32_t> client_counts = {10, 100, 1000};
  vbaoi::SimulationOptions simulation;  // `clients` is replaced by each count
  int oracle_threads = 2;               // line-of-sight rays are cast on this many threads
};

// {"graph": {...}, "runs": [{clients, policies: [...], vbaoi: {...}}], "replay": "..."}.
nlohmann::json vbaoi_report(const Scene& scene, const SceneSource& source, const VbaoiOptions& options);
std::string vbaoi_table(const nlohmann::json& report);
// The claims ledger's VbAoI entries, from a section's runs: channel grouping by PVSn (the method's
// claim) and by SNs only (one sentence of ch. 5.1), each refuted by its first violating pair.
std::vector<ClaimCheck> vbaoi_claims(const nlohmann::json& report);
// Violations that fail the gate: VbAoI's grouping violations, missed updates, renders without
// data and clients outside their node, when the graph's method claims to be conservative.
std::size_t vbaoi_gate_violations(const nlohmann::json& report);
// The command that replays one run.
std::string vbaoi_replay_command(const SceneSource& source, const VbaoiOptions& options, std::uint32_t clients);

}  // namespace cullcheck
