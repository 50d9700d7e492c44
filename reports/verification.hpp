// Holds engine methods to the oracle along a camera path: every method culls every frame, the
// oracle says what is visible, and every building the oracle sees but a method culled is a
// violation with a one-line replay command.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/camera_path.hpp"
#include "engine/method.hpp"
#include "oracle/oracle.hpp"
#include "reports/scene_source.hpp"

namespace cullcheck {

struct VerificationOptions {
  oracle::OracleOptions oracle;
  std::size_t oracle_stride = 1;  // check every n-th frame with the oracle (timings use all)
  std::size_t max_replays = 5;    // violations kept in full per method (all are counted)
  // Command-line flags that rebuild the path (e.g. "--path-kind street_walk --path-seed 1
  // --path-params '{...}'"): an incremental method's violation replays along the whole path.
  std::string path_replay_flags;
  // Every run's PVS is compared with this method's at every frame (when it is in the run):
  // ΔH's claim is to give exactly OH(OS)'s PVS.
  std::string reference_method = "oh_os_conservative";
  // From-region methods (thesis ch. 4) used as a walker would: a PVS computed for the disc of
  // `region_radius` around the eye (turn `region_turn`) serves every frame whose camera stays
  // in that region, and is recomputed around the first camera that leaves it.
  std::vector<std::string> region_methods;
  double region_radius = 1.4142135623730951;  // √2 m: the thesis's 2 m steps (ch. 4.2)
  double region_turn = 0.0;
  // Where a new disc is centred when the walker leaves the old one: at the walker's eye, or at
  // the nearest centre of the circle tiling (Fig. 4.9d, engine/shrinking/circle_tiling.hpp),
  // whose six neighbours a client can compute ahead.
  bool region_on_tiling = false;
};

struct Violation {
  std::size_t frame = 0;
  ObjectId building = 0;
  Camera camera;
  std::string model;          // the oracle model that saw it
  std::string witness;        // the witness ray, described (empty for the exact 2D model)
  std::string replay;         // `cullcheck verify ...` that reproduces it
};

struct MethodRun {
  std::string method;
  bool claims_conservative = false;
  std::vector<double> cull_ms;          // every frame
  std::vector<double> pvs_size;         // every frame
  std::vector<double> checked_pvs_size;  // frames checked by the oracle
  std::vector<double> witnessed_size;    // same frames
  CullStatistics totals;                // summed over frames (cull_ms excluded)
  std::uint64_t violation_count = 0;
  std::size_t frames_with_violations = 0;
  std::vector<Violation> violations;    // the first max_replays
  bool compared_with_reference = false;
  std::size_t frames_differing_from_reference = 0;  // frames whose PVS differs from the reference's
};

struct RegionRun {
  std::string method;
  bool claims_conservative = false;
  double radius = 0.0, turn = 0.0;
  bool on_tiling = false;
  std::vector<double> compute_ms;        // one per region PVS computed
  std::vector<double> pvs_size;          // every frame: the PVS in use
  std::vector<double> point_pvs_size;    // every frame: the reference method's PVS at that camera
  std::vector<double> checked_pvs_size;  // frames checked by the oracle
  std::vector<double> witnessed_size;
  std::uint64_t violation_count = 0;
  std::size_t frames_with_violations = 0;
  std::vector<Violation> violations;
};

struct OracleSummary {
  std::size_t frames_checked = 0;
  std::size_t frames_exact_2d = 0;
  std::size_t frames_ray_sampling = 0;
  std::uint64_t rays_cast = 0;
  double seconds = 0.0;
  double sampling_seconds = 0.0;          // time spent in ray-sampling queries
  double bare_embree_rays_per_second = 0.0;  // the same rays in a bare Embree loop, same run
  oracle::SamplingOptions density;
  std::size_t oracle_stride = 1;
};

struct PathVerification {
  std::vector<MethodRun> runs;
  std::vector<RegionRun> regions;
  OracleSummary oracle;
};

// The replay command for one camera, method and scene.
std::string region_replay_command(const SceneSource& source, const std::string& method, const Camera& centre,
                                  double radius, double turn, const Camera& viewpoint);
std::string replay_command(const SceneSource& source, const std::string& method, const Camera& camera);

PathVerification verify_path(const Scene& scene, const SceneSource& source, const CameraPath& path,
                             const std::vector<std::string>& methods, const MethodOptions& method_options,
                             const VerificationOptions& options);

// Buildings in `visible` missing from `pvs` (both sorted).
std::vector<ObjectId> missing_from(const std::vector<ObjectId>& visible, const std::vector<ObjectId>& pvs);

}  // namespace cullcheck
