// Flags shared by the subcommands of `cullcheck` (one file per subcommand, see subcommands.hpp):
// where the scene and the path come from, the oracle's density, the engine's knobs, from-region
// and VbAoI options. Each group adds its options to a subcommand and resolves them after parsing.
#pragma once

#include <CLI/CLI.hpp>

#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "core/camera_path.hpp"
#include "core/coordinates.hpp"
#include "core/shard.hpp"
#include "engine/method.hpp"
#include "oracle/sampling.hpp"
#include "reports/scene_source.hpp"
#include "reports/vbaoi.hpp"

namespace cullcheck::cli {

// Exit codes (README "Exit codes").
inline constexpr int kExitGateFailed = 1;
inline constexpr int kExitBadInput = 2;
inline constexpr int kExitInternalError = 3;

struct SceneFlags {
  SceneSource source;
  void add(CLI::App& app);
};

// --coordinates world|local: the frame of camera and path JSON that does not say its own
// (core/coordinates.hpp; files that say are read as they say, and a flag that contradicts them
// is an error). Without it such files are scene-local, as cullcheck writes them.
struct CoordinateFlags {
  std::string frame;  // "", "local" or "world"
  void add(CLI::App& app, const std::string& applies_to);
  std::optional<CoordinateFrame> fallback() const;
  // `path` (read from `file`, or "--camera") into scene-local coordinates, refused when every eye
  // lies far outside the scene (require_an_eye_near_the_scene).
  CoordinateConversion localise(CameraPath& path, const Scene& scene, const std::string& file) const;
  // One camera given as JSON on the command line (`flag`: --camera, --from), scene-local.
  Camera camera(const Scene& scene, const std::string& json, const std::string& flag, CoordinateConversion* how = nullptr) const;
  // " --coordinates world" when given, for replays of a path file.
  std::string replay_flag() const;
};

struct PathFlags {
  std::string kind = "street_walk";
  std::uint64_t seed = 1;
  std::string params = "{}";
  std::string file;
  CoordinateFlags coordinates;
  void add(CLI::App& app, int default_frames);
  // The flags that rebuild this path, for replay commands.
  std::string replay_flags() const;
  // The path file (scene-local after `coordinates`) or the generated path; `how` says which
  // frame it was given in.
  CameraPath load(const Scene& scene, CoordinateConversion* how = nullptr) const;
  // One camera (`--camera` JSON) as a one-frame path when given, else the path.
  CameraPath load(const Scene& scene, const std::string& camera_json, CoordinateConversion* how = nullptr) const;
  // The name of where the cameras came from, for coordinates_line.
  std::string source_name(const std::string& camera_json) const;
};

// --shard K/N (core/shard.hpp), checked as it is parsed; `what` says what the shard does.
void add_shard_flag(CLI::App& app, Shard& shard, const std::string& what);

// Parses a JSON flag value, raising InputError naming the flag.
nlohmann::json parse_json_flag(const std::string& text, const std::string& field);

struct SamplingFlags {
  oracle::SamplingOptions sampling;
  void add(CLI::App& app);
};

// The engine's tuning knobs, the same on every subcommand that runs methods.
struct MethodFlags {
  MethodOptions options;
  std::string online_priority = "coverage";
  void add(CLI::App& app);
  // The flags that give `options` where they differ from the defaults (leading space each), for
  // replay commands: an incremental method's failure replays only with the knobs it ran with.
  std::string replay_flags() const;
};

// From-region methods along a path (thesis ch. 4): which, and the region each PVS serves.
struct RegionFlags {
  std::string methods;
  double radius = 1.4142135623730951;
  double turn = 0.0;
  std::string placement = "eye";
  void add(CLI::App& app, const std::string& default_methods);
};

// VbAoI (issue 5): the graph's from-region method and the simulation's knobs. `prefix` keeps
// the names apart where other flags live (report: "vbaoi-").
struct VbaoiFlags {
  VbaoiOptions options;
  std::string sampling = "boundary", symmetry = "intersection";
  void add(CLI::App& app, const std::vector<std::uint32_t>& default_clients, const std::string& prefix = "");
  const VbaoiOptions& resolved();
};

// "all", "none"/"" or a comma-separated list checked against `names`.
std::vector<std::string> parse_methods(const std::string& list, const std::vector<std::string>& names = method_names());

nlohmann::json pvs_json(const CullResult& r);

// `region --from` and `cell --from`: the oracle's view from one eye (camera JSON) against a
// from-region PVS, into out["from"]; the gate's exit code when a method that claims to be
// conservative missed what it saw, else 0 (also when no eye was given).
int check_from(const Scene& scene, const std::optional<Camera>& from, const oracle::SamplingOptions& sampling,
               const std::vector<ObjectId>& pvs, const RegionCullingMethod& method, nlohmann::json& out);

}  // namespace cullcheck::cli
