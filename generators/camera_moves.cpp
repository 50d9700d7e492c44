#include "generators/camera_moves.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/errors.hpp"
#include "core/scene_io.hpp"
#include "generators/angles.hpp"

namespace cullcheck::generators {
namespace {
constexpr MoveKind kKinds[] = {MoveKind::forward, MoveKind::backward, MoveKind::left, MoveKind::right,
                               MoveKind::turn,    MoveKind::stop,     MoveKind::rise};
}  // namespace

const char* to_string(MoveKind k) {
  switch (k) {
    case MoveKind::forward: return "forward";
    case MoveKind::backward: return "backward";
    case MoveKind::left: return "left";
    case MoveKind::right: return "right";
    case MoveKind::turn: return "turn";
    case MoveKind::stop: return "stop";
    case MoveKind::rise: return "rise";
  }
  return "?";
}

Camera apply_move(Camera c, const Move& m) {
  const Vec2 forward{std::cos(c.yaw), std::sin(c.yaw)}, left{-forward.y, forward.x};
  auto step = [&](Vec2 d) { c.position = {c.position.x + d.x * m.amount, c.position.y + d.y * m.amount, c.position.z}; };
  switch (m.kind) {
    case MoveKind::forward: step(forward); break;
    case MoveKind::backward: step(forward * -1.0); break;
    case MoveKind::left: step(left); break;
    case MoveKind::right: step(left * -1.0); break;
    case MoveKind::turn: c.yaw = wrap_azimuth(c.yaw + m.amount); break;
    case MoveKind::rise: c.position.z = std::max(0.0, c.position.z + m.amount); break;
    case MoveKind::stop: break;
  }
  return c;
}

CameraPath path_of_moves(const Camera& start, const std::vector<Move>& moves) {
  CameraPath path;
  path.kind = "moves";
  path.frames.push_back(start);
  for (const Move& m : moves) path.frames.push_back(apply_move(path.frames.back(), m));
  return path;
}

nlohmann::json moves_params(const Camera& start, const std::vector<Move>& moves) {
  nlohmann::json list = nlohmann::json::array();
  for (const Move& m : moves)
    list.push_back(m.kind == MoveKind::stop ? nlohmann::json::array({"stop"}) : nlohmann::json::array({to_string(m.kind), m.amount}));
  return {{"start", nlohmann::json::parse(camera_to_json_text(start))}, {"moves", list}};
}

CameraPath moves_path(const nlohmann::json& params) {
  if (!params.is_object() || !params.contains("start")) throw InputError("path", "start", "the moves path needs a start camera");
  const Camera start = camera_from_json_text(params.at("start").dump(), "path.start");
  std::vector<Move> moves;
  const nlohmann::json list = params.value("moves", nlohmann::json::array());
  if (!list.is_array()) throw InputError("path", "moves", "must be a list of moves like [\"left\", 5.0]");
  for (std::size_t i = 0; i < list.size(); ++i) {
    const std::string field = "moves[" + std::to_string(i) + "]";
    const nlohmann::json& m = list[i];
    if (!m.is_array() || m.empty() || !m[0].is_string()) throw InputError("path", field, "must be like [\"left\", 5.0]");
    const std::string name = m[0].get<std::string>();
    const auto kind = std::find_if(std::begin(kKinds), std::end(kKinds), [&](MoveKind k) { return name == to_string(k); });
    if (kind == std::end(kKinds))
      throw InputError("path", field, "unknown move '" + name + "' (known: forward, backward, left, right, turn, stop, rise)");
    Move move{*kind, 0.0};
    if (*kind != MoveKind::stop) {
      if (m.size() != 2 || !m[1].is_number() || !std::isfinite(m[1].get<double>()))
        throw InputError("path", field, "needs one finite amount (metres, or radians for a turn)");
      move.amount = m[1].get<double>();
    }
    moves.push_back(move);
  }
  return path_of_moves(start, moves);
}

}  // namespace cullcheck::generators
