// Camera paths made of explicit moves (path kind "moves"): the ΔH fuzzer's paths (thesis ch.
// 3.1.3, Table 3.1, Fig. 3.10) as replayable data. A path is a start camera and a list of moves;
// frame 0 is the start and each move makes the next frame:
//   forward/backward/left/right <metres>  step along or across the plan view direction
//   turn <radians>                        yaw change, signed, kept in [0, 2π)
//   rise <metres>                         height change, clamped at the ground
//   stop                                  the same camera again (stop-and-go)
// JSON parameters: {"start": <camera>, "moves": [["left", 5.0], ["turn", -0.3], ["stop"], ...]}.
#pragma once

#include <nlohmann/json.hpp>
#include <vector>

#include "core/camera.hpp"
#include "core/camera_path.hpp"

namespace cullcheck::generators {

enum class MoveKind { forward, backward, left, right, turn, stop, rise };

struct Move {
  MoveKind kind = MoveKind::stop;
  double amount = 0.0;  // metres (steps, rise) or radians (turn)
};

const char* to_string(MoveKind kind);
Camera apply_move(Camera camera, const Move& move);
CameraPath path_of_moves(const Camera& start, const std::vector<Move>& moves);

// The "moves" path kind's parameters, both ways; bad input throws InputError naming the field.
nlohmann::json moves_params(const Camera& start, const std::vector<Move>& moves);
CameraPath moves_path(const nlohmann::json& params);

}  // namespace cullcheck::generators
