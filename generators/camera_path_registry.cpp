// Camera paths by kind, for the CLI and for replay commands (see camera_paths.hpp).
#include <nlohmann/json.hpp>

#include "core/errors.hpp"
#include "generators/camera_moves.hpp"
#include "generators/camera_paths.hpp"
#include "generators/params_json.hpp"

namespace cullcheck::generators {

const std::vector<std::string>& camera_path_kinds() {
  static const std::vector<std::string> kinds = {"street_walk", "fly_through", "moves", "plaza_crossing"};
  return kinds;
}

CameraPath make_camera_path(const std::string& kind, const Scene& scene, std::uint64_t seed, const nlohmann::json& params) {
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

}  // namespace cullcheck::generators
