// Camera paths by kind, for the CLI and for replay commands (see camera_paths.hpp).
#include <nlohmann/json.hpp>

#include "core/errors.hpp"
#include "generators/camera_moves.hpp"
#include "generators/camera_paths.hpp"
#include "generators/params_json.hpp"
#include "generators/scene_timeline_gen.hpp"

namespace cullcheck::generators {

const std::vector<std::string>& camera_path_kinds() {
  static const std::vector<std::string> kinds = {"street_walk", "fly_through", "moves", "plaza_crossing"};
  return kinds;
}

namespace {

CameraPath path_of_kind(const std::string& kind, const Scene& scene, std::uint64_t seed, const nlohmann::json& params) {
  if (kind == "street_walk") {
    StreetWalkParams p;
    overlay_params_json(p, params, "path", kind);
    return street_walk(scene, p, seed);
  }
  if (kind == "fly_through") {
    FlyThroughParams p;
    overlay_params_json(p, params, "path", kind);
    return fly_through(scene, p, seed);
  }
  if (kind == "moves") return moves_path(params);
  if (kind == "plaza_crossing") {
    PlazaCrossingParams p;
    overlay_params_json(p, params, "path", kind);
    return plaza_crossing(scene, p);
  }
  throw InputError("path", "kind", "unknown camera path kind '" + kind + "' (known: street_walk, fly_through, moves, plaza_crossing)");
}

}  // namespace

// Any kind takes a "timeline" object (scene_timeline_gen.hpp), seeded by the path's seed.
CameraPath make_camera_path(const std::string& kind, const Scene& scene, std::uint64_t seed, const nlohmann::json& params) {
  if (!params.is_object() || !params.contains("timeline")) return path_of_kind(kind, scene, seed, params);
  nlohmann::json rest = params;
  rest.erase("timeline");
  CameraPath path = path_of_kind(kind, scene, seed, rest);
  TimelineParams t;
  overlay_params_json(t, params["timeline"], "path", "timeline");
  path.events = scene_timeline(scene, path.frames.size(), t, seed);
  return path;
}

}  // namespace cullcheck::generators
