// Holds methods to the oracle along a camera path: every method culls every frame, the oracle
// says what is visible, and every object the oracle sees but a method culled is a violation with
// a one-line replay command. The methods are the engine's or outside subjects (subjects/): all
// behind CullingMethod, held to the same checks.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/camera_path.hpp"
#include "core/shard.hpp"
#include "engine/method.hpp"
#include "oracle/oracle.hpp"
#include "reports/scene_source.hpp"

namespace cullcheck {

struct VerificationOptions {
  oracle::OracleOptions oracle;
  std::size_t oracle_stride = 1;  // check every n-th frame with the oracle (timings use all)
  // Re-cast the first frame's rays in a bare Embree loop for at least 0.2 s, the report's
  // yardstick for the oracle's speed (OracleSummary::bare_embree_rays_per_second). Off for the
  // fuzzer's many small cases, where it would be most of the time.
  bool measure_bare_embree = true;
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
  // Also hold every checked frame to the pixel oracle (oracle/pixel_oracle.hpp): misdrawn pixels
  // per method; approximate methods are judged by their pixel_error_budget. Always on when a
  // method has a budget.
  bool pixels = false;
  // The index along the original path of the first camera given (`gate --frame N` checks one
  // frame of a path): frames are numbered from it in results, replays and set_frame.
  std::size_t first_frame = 0;
  // The frame (its number along the original path) each run keeps as its FrameSnapshot, when it
  // is checked; without it, each run keeps its worst checked frame.
  std::optional<std::size_t> snapshot_frame;
  // A shard checks only its share of the checked frames (the n-th checked frame is shard n mod
  // N's); every shard runs every method along the whole path, since an incremental method's
  // answer depends on the frames before. merge_verifications joins the shards.
  Shard shard;
  // Hold every built-in method to conservativeness whatever it claims (`--hold-conservative`):
  // a paper's claim the engine does not gate, e.g. that range detection (rdt) drops only what is
  // outside the frustum. Replays carry the flag.
  bool hold_conservative = false;
};

// One checked frame of one method, kept for the report page's map: the camera, the PVS, what the
// oracle saw, what the method missed (seen, not in the PVS) and the witness rays of the missed.
struct FrameSnapshot {
  std::size_t frame = 0;
  Camera camera;
  std::vector<ObjectId> pvs, seen, missed;  // sorted
  std::vector<oracle::WitnessRay> witness_rays;  // one per missed object that has one
  std::size_t overestimate = 0;  // PVS objects the oracle did not see
};
// Whether `a` is a worse frame than `b`: more missed objects, then more over-estimate (so the
// first of equally bad frames is kept).
bool worse_frame(const FrameSnapshot& a, const FrameSnapshot& b);

struct Violation {
  std::size_t frame = 0;
  ObjectId building = 0;
  Camera camera;
  std::string model;          // the oracle model that saw it
  std::string witness;        // the witness ray, described (empty for the exact 2D model)
  std::string replay;         // `cullcheck verify ...` that reproduces it
};

// A method under test and the command that replays a failure at one of its frames.
struct MethodUnderTest {
  std::unique_ptr<CullingMethod> method;
  std::function<std::string(std::size_t frame, const Camera& camera)> replay;
  bool outside = false;  // an outside subject (its PVS is compared with every built-in method's)
};

// The engine's methods by name (replayed by `cullcheck verify`), skipping those that cannot
// run on `scene` (method_unavailable_reason) into `skipped` as {name, reason}.
std::vector<MethodUnderTest> builtin_methods(const Scene& scene, const SceneSource& source, const std::vector<std::string>& names,
                                             const MethodOptions& method_options, const VerificationOptions& options,
                                             std::vector<std::pair<std::string, std::string>>* skipped = nullptr);

// Where a run stopped because an outside subject failed (crashed, hung, lied): every result
// before `frame` is kept.
struct Abort {
  std::string method;
  std::int64_t frame = -1;  // -1: during the handshake
  std::string kind;         // SubjectError::kind_name
  std::string message;
};

// Violations of one method over a set of checked frames: all counted, the first few kept.
struct ViolationTally {
  std::uint64_t count = 0;
  std::size_t frames = 0;  // frames with at least one violation
  std::vector<Violation> kept;
};

struct MethodRun {
  std::string method;
  bool claims_conservative = false;
  bool outside = false;
  std::optional<std::uint64_t> pixel_error_budget;  // approximate methods' misdrawn pixels per frame
  std::vector<double> cull_ms;          // every frame
  std::vector<std::size_t> answered_frames;  // the number of each of those frames along the path
  std::vector<double> pvs_size;         // every frame
  std::vector<double> checked_pvs_size;  // frames checked by the oracle
  std::vector<double> witnessed_size;    // same frames
  std::vector<std::size_t> checked_frames;  // the number of each checked frame along the path
  std::optional<FrameSnapshot> snapshot;  // the worst checked frame, or options.snapshot_frame
  CullStatistics totals;                // summed over frames (cull_ms excluded)
  std::uint64_t violation_count = 0;
  std::size_t frames_with_violations = 0;
  std::vector<Violation> violations;    // the first max_replays
  // Witnesses of objects this method culled, re-cast in double precision before they count as
  // violations (oracle/witness_recheck.hpp), over every checked frame; dropped ones do not count.
  oracle::WitnessRecheckCounts witness_recheck;
  bool compared_with_reference = false;
  std::size_t frames_differing_from_reference = 0;  // frames whose PVS differs from the reference's
  // Frames the method could not answer (CullingMethod::unsupported_camera), with the first reason.
  std::size_t frames_skipped = 0;
  std::string skip_reason;
  std::vector<double> protocol_ms;  // every frame (outside subjects: time in the protocol)
  std::vector<double> background_ms;  // every frame (CullStatistics::background_ms)
  // Outside subjects: frames whose PVS equals each built-in method's, by method name.
  std::vector<std::pair<std::string, std::size_t>> frames_equal_to;
  // The pixel oracle (VerificationOptions::pixels), over checked frames.
  std::vector<double> misdrawn_pixels;  // per checked frame
  std::vector<std::uint64_t> blob_per_frame;      // the largest blob per checked frame
  std::vector<std::size_t> pixel_frames;          // the frame number of each of them
  std::uint64_t misdrawn_total = 0;
  std::size_t error_frames = 0;         // checked frames with any misdrawn pixel
  std::uint64_t largest_blob = 0;       // largest 4-connected blob of misdrawn pixels, any frame
  std::uint64_t most_misdrawn = 0;      // the worst frame's misdrawn pixels
  std::size_t frames_over_budget = 0;   // approximate methods: frames above pixel_error_budget
  std::vector<Violation> over_budget;   // the first max_replays of them (building = the worst object)
  // Before settle_violations: whether the method claims conservativeness for every camera, the
  // checked frames its claim covers, and the violations of every checked frame and of those.
  bool claims_every_camera = false;
  std::size_t frames_claimed = 0;
  ViolationTally every_frame, claimed_frames;
};

// Sets a run's claims_conservative and violations from its tallies (the gate's rule, in
// verification.cpp): at the end of verify_path, and again after shards are merged.
void settle_violations(MethodRun& run);

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
  std::vector<std::size_t> checked_frames;  // the number of each of them along the path
  std::uint64_t violation_count = 0;
  std::size_t frames_with_violations = 0;
  std::vector<Violation> violations;
  oracle::WitnessRecheckCounts witness_recheck;  // as MethodRun's
};

struct OracleSummary {
  std::size_t frames_checked = 0;
  std::size_t frames_exact_2d = 0;
  std::size_t frames_ray_sampling = 0;
  std::uint64_t rays_cast = 0;
  double seconds = 0.0;
  double sampling_seconds = 0.0;          // time spent in ray-sampling queries
  double bare_embree_rays_per_second = 0.0;  // the same rays in a bare Embree loop, same run
  double bare_embree_packet_rays_per_second = 0.0;  // the same, in packets as the oracle casts them
  oracle::SamplingOptions density;
  std::size_t oracle_stride = 1;
  std::uint64_t grazing_rays = 0;              // of rays_cast: silhouette-grazing rays
  std::uint64_t rays_skipped = 0;              // not cast: their object was witnessed (OracleResult::rays_skipped)
  oracle::WitnessRecheckCounts witness_recheck;  // distinct witnesses re-cast, over all frames
};

struct PixelSummary {
  bool enabled = false;
  std::size_t frames = 0;
  std::uint64_t rays = 0;
  double seconds = 0.0;
};

struct PathVerification {
  std::vector<MethodRun> runs;
  // The frames the oracle checked (numbers along the path) and what it saw at each, sorted ids:
  // what a re-run of the methods with other knobs is held to (knob_sweep.hpp).
  std::vector<std::size_t> checked_frames;
  std::vector<std::vector<ObjectId>> checked_visible;
  std::vector<RegionRun> regions;
  OracleSummary oracle;
  PixelSummary pixels;
  std::vector<std::pair<std::string, std::string>> skipped_methods;  // {name, why}
  std::size_t frames_run = 0;        // frames every method answered (the whole path unless aborted)
  std::optional<Abort> aborted;
};

// The replay command for one camera, method and scene.
std::string region_replay_command(const SceneSource& source, const std::string& method, const Camera& centre,
                                  double radius, double turn, const Camera& viewpoint);
std::string replay_command(const SceneSource& source, const std::string& method, const Camera& camera);

PathVerification verify_path(const Scene& scene, const SceneSource& source, const CameraPath& path,
                             const std::vector<std::string>& methods, const MethodOptions& method_options,
                             const VerificationOptions& options);
// The same for any methods under test. A SubjectError from an outside subject stops the run at
// that frame: the result holds every frame before it and says where and why (`aborted`).
PathVerification verify_path(const Scene& scene, const SceneSource& source, const CameraPath& path,
                             std::vector<MethodUnderTest>& methods, const MethodOptions& method_options,
                             const VerificationOptions& options);

// Buildings in `visible` missing from `pvs` (both sorted).
std::vector<ObjectId> missing_from(const std::vector<ObjectId>& visible, const std::vector<ObjectId>& pvs);

}  // namespace cullcheck
