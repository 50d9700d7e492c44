// The ε trade (issue 4): for each from-region method and each disc radius, a walker's PVS
// reuse along a path — how many PVS were computed, how many frames each served at the path's
// speed, what one cost, and how much larger it is than the point PVS (OH(OS) at every frame).
// No oracle here: accuracy is the regions[] runs' business.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/camera_path.hpp"
#include "core/scene.hpp"
#include "engine/method.hpp"

namespace cullcheck {

// One row per method and radius: {method, radius, turn, pvs_computed, frames_per_pvs,
// seconds_per_pvs (at the path's frame rate), compute_ms_median, pvs_mean, point_pvs_mean,
// increase_over_point_pvs}; shrink_minkowski's rows also give minkowski_occluders {occluders,
// faces_removed, invalid_footprint, too_low}: what its preprocessing made of the buildings at that ε.
nlohmann::json region_radius_sweep(const Scene& scene, const CameraPath& path, const std::vector<std::string>& methods,
                                   const std::vector<double>& radii, double turn, bool on_tiling, const MethodOptions& options);
// The rows as a printed table.
std::string region_sweep_table(const nlohmann::json& rows);

}  // namespace cullcheck
