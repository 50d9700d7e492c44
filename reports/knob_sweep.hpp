// The speed/accuracy trade of the engine's knobs (issue 12's Pareto plot): each point method the
// knob affects runs along the path again at every value, and its PVS at the frames the oracle
// checked in the main run is held to what the oracle saw there. Knobs: horizon_bins (azimuth
// resolution of every horizon), quadtree_leaf_size (frustum and horizon methods' quadtree),
// delta_radius, delta_height, delta_turn (guarded ΔH's motion region). ε of the region methods is
// swept by --region-sweep (region_sweep.hpp).
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/camera_path.hpp"
#include "core/scene.hpp"
#include "engine/method.hpp"
#include "reports/verification.hpp"

namespace cullcheck {

struct KnobSweep {
  std::string knob;
  std::vector<double> values;
};

// "horizon_bins=256,1024,4096": InputError naming the flag when the knob is unknown or a value
// is not a number, not positive, or (for the integer knobs) not a whole number up to 2^20.
KnobSweep parse_knob_sweep(const std::string& text);
// The methods whose PVS or cost the knob changes, in report order.
std::vector<std::string> methods_affected_by(const std::string& knob);
// `options` with the knob set to `value`.
MethodOptions with_knob(MethodOptions options, const std::string& knob, double value);

// One row per knob, value and method of `methods` the knob affects: {knob, value, method,
// run_setting (the value the main run used), frames, cull_ms_median, cull_ms_p95, pvs_mean,
// pvs_mean_checked_frames, witnessed_mean, overestimation, misses}. `misses` counts objects the
// main run's oracle saw at a checked frame that this PVS culled: the oracle's answer is not cast
// again (nor its witnesses re-checked), so a non-zero count is a lead to replay with `cullcheck
// verify --<knob> <value>`, not yet a verdict. `main` must be the verification of the same path.
nlohmann::json knob_sweep(const Scene& scene, const CameraPath& path, const std::vector<std::string>& methods,
                          const MethodOptions& options, const std::vector<KnobSweep>& sweeps, const PathVerification& main);

// One row before it is summed up: every frame's time and PVS, and the PVS at each frame `main`
// checked. A shard's `main` checked its share of the frames only; merge_knob_rows joins them.
struct KnobRow {
  std::string knob, method;
  double value = 0.0;
  bool run_setting = false;
  std::vector<double> cull_ms, pvs;  // every frame the method answered
  std::vector<std::size_t> checked_frames;
  std::vector<double> checked_pvs, witnessed;  // at those frames
  std::uint64_t misses = 0;
};
std::vector<KnobRow> knob_sweep_rows(const Scene& scene, const CameraPath& path, const std::vector<std::string>& methods,
                                     const MethodOptions& options, const std::vector<KnobSweep>& sweeps, const PathVerification& main);
nlohmann::json knob_sweep_json(const std::vector<KnobRow>& rows);
nlohmann::json knob_row_to_raw_json(const KnobRow& row);
KnobRow knob_row_from_raw_json(const nlohmann::json& j, const std::string& what);
// The rows as a printed table.
std::string knob_sweep_table(const nlohmann::json& rows);

}  // namespace cullcheck
