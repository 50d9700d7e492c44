#include "reports/region_sweep.hpp"

#include <cstdio>

#include "engine/shrinking/minkowski_shrinking.hpp"

#include "reports/statistics.hpp"
#include "reports/verification.hpp"

namespace cullcheck {

namespace {

// What shrink_minkowski's preprocessing makes of the scene's buildings for one ε: occluders, and
// the buildings that cast no shadow, by reason (minkowski_shrinking.hpp).
nlohmann::json minkowski_occluder_counts(const Scene& scene, double epsilon) {
  MinkowskiOccluderCounts n;
  for (const Building& b : scene.buildings) switch (minkowski_occluder(b, epsilon).outcome) {
      case MinkowskiOutcome::occluder: ++n.occluders; break;
      case MinkowskiOutcome::faces_removed: ++n.faces_removed; break;
      case MinkowskiOutcome::invalid_footprint: ++n.invalid_footprint; break;
      case MinkowskiOutcome::too_low: ++n.too_low; break;
    }
  return {{"occluders", n.occluders}, {"faces_removed", n.faces_removed}, {"invalid_footprint", n.invalid_footprint},
          {"too_low", n.too_low}};
}

}  // namespace

nlohmann::json region_radius_sweep(const Scene& scene, const CameraPath& path, const std::vector<std::string>& methods,
                                   const std::vector<double>& radii, double turn, bool on_tiling, const MethodOptions& options) {
  VerificationOptions verification;
  verification.oracle_stride = path.frames.size() + 1;  // frame 0 only: the sweep is about cost
  verification.region_methods = methods;
  verification.region_turn = turn;
  verification.region_on_tiling = on_tiling;
  nlohmann::json rows = nlohmann::json::array();
  for (double radius : radii) {
    verification.region_radius = radius;
    const PathVerification v = verify_path(scene, SceneSource{}, path, {"oh_os_conservative"}, options, verification);
    for (const RegionRun& r : v.regions) {
      const double frames = static_cast<double>(r.pvs_size.size()), computed = static_cast<double>(r.compute_ms.size());
      const double point = mean(r.point_pvs_size);
      rows.push_back({{"method", r.method},
                      {"radius", radius},
                      {"turn", turn},
                      {"placement", on_tiling ? "circle_tiling" : "at_eye"},
                      {"pvs_computed", r.compute_ms.size()},
                      {"frames_per_pvs", computed > 0 ? frames / computed : 0.0},
                      {"seconds_per_pvs", computed > 0 ? frames / computed / path.frames_per_second : 0.0},
                      {"compute_ms_median", median(r.compute_ms)},
                      {"pvs_mean", mean(r.pvs_size)},
                      {"point_pvs_mean", point},
                      {"increase_over_point_pvs", point > 0 ? mean(r.pvs_size) / point - 1.0 : 0.0}});
      if (r.method == "shrink_minkowski") rows.back()["minkowski_occluders"] = minkowski_occluder_counts(scene, radius);
    }
  }
  return rows;
}

std::string region_sweep_table(const nlohmann::json& rows) {
  std::string out;
  char line[256];
  std::snprintf(line, sizeof line, "%-32s %8s %8s %10s %10s %9s %10s\n", "region method", "radius", "pvs", "frames/pvs",
                "ms/pvs", "pvs_mean", "increase");
  out += line;
  for (const auto& r : rows) {
    std::snprintf(line, sizeof line, "%-32s %8.2f %8zu %10.1f %10.3f %9.1f %9.0f%%\n", r["method"].get<std::string>().c_str(),
                  r["radius"].get<double>(), r["pvs_computed"].get<std::size_t>(), r["frames_per_pvs"].get<double>(),
                  r["compute_ms_median"].get<double>(), r["pvs_mean"].get<double>(),
                  100.0 * r["increase_over_point_pvs"].get<double>());
    out += line;
  }
  return out;
}

}  // namespace cullcheck
