// Fuzzing a culling system (README "Fuzzing an outside program"): RapidCheck draws
// small seeded scenes (cities, and mesh scenes with openings) and short camera paths of the
// kinds real cullers get wrong (generators/fuzz_cases.hpp), each case is sent to a fresh run of
// the subject over the subject protocol and held to the oracle like `cullcheck gate`, and the
// first failure is shrunk to a small case. A failure is a miss by a subject that claims to be
// conservative (or a misdrawn pixel), a frame above an approximate subject's pixel budget, or
// the subject crashing, hanging or lying.
//
// The same loop runs built-in engine methods in process instead (FuzzOptions::methods): every
// case's oracle answer checks all of them at once, which makes it the long "soak" run that counts
// oracle-checked frames per method (README "Soak runs").
//
// The same seed and budget draw the same cases on every machine; the subject's own answers
// decide the rest.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "core/shard.hpp"
#include "generators/fuzz_cases.hpp"
#include "oracle/sampling.hpp"
#include "reports/claims.hpp"
#include "reports/verification.hpp"
#include "subjects/protocol.hpp"

namespace cullcheck {

struct FuzzOptions {
  std::string subject;        // command line, run by /bin/sh -c
  std::vector<std::string> methods;  // or built-in methods by name, run in process (subject empty)
  int budget = 100;           // cases that must pass
  std::uint64_t seed = 1;
  double frame_timeout = 10.0;
  double hello_timeout = 60.0;
  oracle::SamplingOptions sampling;
  std::string work_dir;       // each case's scene files go here (a temporary folder when empty)
  bool pixels = true;         // hold every frame to the pixel oracle too
  bool hold_conservative = false;  // built-in methods judged conservative whatever they claim (reports/held_conservative.hpp)
  // Run only the cases this shard owns (the n-th case drawn is shard n mod N's; every shard
  // draws every case, which is cheap, so each case is the one the unsharded run draws). A shard
  // stops at its own first failure and shrinks it; merge_fuzz_shards keeps the lowest.
  Shard shard;
};

struct FuzzFailure {
  generators::FuzzCase minimal;
  std::string method;           // the method that failed (the subject's name for a subject)
  std::string message;          // the check that failed, with the first violation
  bool subject_error = false;   // crashed, hung or lied rather than culled wrongly
  PathVerification verification;  // of the minimal case
  std::map<std::size_t, std::vector<ObjectId>> pvs_by_frame;  // the subject's answers in it
  std::size_t objects = 0, triangles = 0;
  std::size_t first_objects = 0, first_frames = 0;  // the first failing case's, before shrinking
};

struct FuzzResult {
  std::string subject_name;     // the subject's name, or the built-in methods' names joined by commas
  bool built_in = false;        // built-in methods (FuzzOptions::methods) rather than a subject
  bool held_conservative = false;  // FuzzOptions::hold_conservative: judged conservative whatever they claim
  std::vector<std::string> methods;
  protocol::Ready ready;
  int cases = 0;                // cases run up to and including the first failure (all, when none failed)
  int shrink_runs = 0;          // cases run while shrinking it
  int shrinks_accepted = 0;     // of those, the smaller cases that still failed
  double seconds_to_failure = 0.0, seconds_total = 0.0;
  std::map<std::string, int> kinds;   // cases run by path kind: that the hard cases were reached
  std::map<std::string, int> scenes;  // by scene generator
  // Frames whose answer the oracle checked, and frames the method skipped (an orthographic camera
  // for a horizon method), by method, over the cases before the first failure.
  std::map<std::string, std::uint64_t> checked_frames, skipped_frames;
  std::uint64_t oracle_frames = 0;  // oracle answers computed (one per frame, shared by the methods)
  // Witnesses of misses re-cast in double precision before they count (oracle/witness_recheck.hpp),
  // over the same cases: dropped ones were single-precision artefacts and failed nothing.
  oracle::WitnessRecheckCounts witness_recheck;
  std::map<std::string, oracle::WitnessRecheckCounts> witness_recheck_by_method;
  std::optional<FuzzFailure> failure;
  // Sharded runs (FuzzOptions::shard): the number of the first failing case drawn (-1: none),
  // and one record per case run before it (and it), for merge_fuzz_shards to count the cases
  // the unsharded run would have run.
  std::int64_t first_failing_case = -1;
  nlohmann::json per_case = nlohmann::json::array();
};

// The point methods that claim conservativeness (the soak run's `--method conservative`).
std::vector<std::string> conservative_method_names();

// Throws SubjectError when the subject cannot even answer a hello for a one-building scene, and
// InputError for an unknown method name.
FuzzResult fuzz_subject(const FuzzOptions& options);

// The minimal counterexample as a self-contained folder: scene.json, scene.glb, path.json
// (and camera.json for one frame), replay.sh (`cullcheck gate` on those files), case.json (what
// failed, the scene's size, the time to find it) and the pictures map.png and frame.png.
// Returns the replay command.
std::string write_counterexample(const FuzzResult& result, const FuzzOptions& options, const std::string& dir);

nlohmann::json fuzz_json(const FuzzResult& result);
// fuzz_json of a shard (FuzzOptions::shard), with its raw records under "shard".
nlohmann::json fuzz_shard_json(const FuzzResult& result, const FuzzOptions& options);
// The fuzz_json of the unsharded run from N shards' fuzz_shard_json (timings aside): the failure
// (and its counterexample folder) of the shard whose first failing case comes first, the counts
// over the cases up to it. Throws InputError when the files are not one run's shards.
nlohmann::json merge_fuzz_shards(const std::vector<nlohmann::json>& documents, const std::vector<std::string>& names);
// The lines `cullcheck fuzz` prints: cases by kind, and the shrunk failure.
std::string fuzz_summary(const FuzzResult& result, const std::string& counterexample_dir);
// The claims ledger's entry: the subject's declared claim, refuted by the fuzzer's counterexample
// (`replay`) or holding over the budget. For built-in methods, one entry per method.
ClaimCheck fuzz_claim(const FuzzResult& result, const std::string& replay);
std::vector<ClaimCheck> fuzz_claims(const FuzzResult& result, const std::string& replay);

}  // namespace cullcheck
