// report.json (schema documented in README.md, "report.json"): one document per run with the
// scene, the path, the oracle's model and density, one entry per method (speed and accuracy
// side by side) and the claims ledger. Everything but the fields named *_ms*, *seconds* and
// *per_second* (and "machine") is a function of the inputs: the same seed gives the same bytes.
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "core/camera_path.hpp"
#include "core/coordinates.hpp"
#include "core/scene.hpp"
#include "engine/method.hpp"
#include "reports/claims.hpp"
#include "reports/gate_verdict.hpp"
#include "reports/scene_source.hpp"
#include "reports/verification.hpp"

namespace cullcheck {

inline constexpr int kReportSchemaVersion = 1;

struct ReportInputs {
  const Scene* scene = nullptr;
  SceneSource source;
  std::optional<formats::ImportReport> import;  // what reading a footprint file did (scene.import)
  const CameraPath* path = nullptr;
  std::string path_parameters_json = "{}";
  std::optional<CoordinateConversion> coordinates;  // the frame the path was given in (path.coordinates)
  MethodOptions method_options;
  const PathVerification* verification = nullptr;
  std::vector<ClaimCheck> claims;
  GateThresholds thresholds;
  // The map's frame (report.json "map", reports/html/frame_map.hpp): this method's snapshot, or
  // (empty) the worst; `map_frame` says the snapshots were taken at a chosen frame.
  std::string map_method;
  std::optional<std::size_t> map_frame;
  std::string path_replay_flags;  // the flags that rebuild the path (path.replay_flags)
};

nlohmann::json build_report(const ReportInputs& in);
// build_report in two parts: what the scene and path are (schema_version, tool, machine, scene,
// path: needs in.scene and in.path), and what the run found, added to such a header (needs
// in.verification, in.claims, in.method_options, the map's choice; the scene's replay flags are
// the header's). `cullcheck merge` adds a merged run's results to a shard's header.
nlohmann::json report_header(const ReportInputs& in);
nlohmann::json report_results(const ReportInputs& in, nlohmann::json header);
// Speed-ups measured in the run, as ratios of the same statistic of two methods over the same
// frames, next to the thesis's Table 3.2 culling-time speed-ups where it has one: OH(IS) vs
// OH(OS), OH(IS) vs ΔH, OH(OS) vs ΔH (for both ΔH variants), frustum vs OH(OS).
nlohmann::json speedups_json(const PathVerification& v);
// The engine's knobs as report.json writes them (runs[].parameters; a shard's method_options).
nlohmann::json method_options_json(const MethodOptions& options);
// A report.json without what is timed (keys holding "_ms", "seconds", "per_second" or
// "speedup", keys starting "ms_", "machine", and "threads", which says how a run was spread, not
// what it found): what the same inputs give byte for byte, on any machine, any
// number of threads, sharded or not.
nlohmann::json without_timings(const nlohmann::json& report);
// The per-method table printed after a run.
std::string summary_table(const PathVerification& v);
// Total violations of methods that claim to be conservative (the CI gate's number).
std::uint64_t conservative_violations(const PathVerification& v);

}  // namespace cullcheck
