// The subject protocol, version 1 (README "The subject protocol"): JSON lines between cullcheck
// and an outside culling system on the system's stdin and stdout. One message per line.
//
//   cullcheck -> subject   {"type":"hello","protocol":1,"scene":{...},"frames":N,"matrix_convention":...}
//   subject -> cullcheck   {"type":"ready","name":"my-culler","claims":"conservative"}
//                       or {"type":"ready","name":"my-culler","claims":"approximate","pixel_error_budget":40}
//                          optional "projections": ["perspective","orthographic","omnidirectional"]
//                          (default ["perspective"]): the cameras it takes
//   cullcheck -> subject   {"type":"frame","frame":i,"time":t,"camera":{...},"view":M,"projection":P,"resolution":[w,h]}
//   subject -> cullcheck   {"type":"visible","frame":i,"ids":[...],"cull_ms":0.4}   (cull_ms optional)
//   ... one frame at a time, in order ...
//   cullcheck -> subject   {"type":"bye"}, then stdin closes; the subject exits.
//
// "ids" are the objects the subject does not cull (any order; repeats are ignored). The hello's
// scene names the files to load (the scene as glTF binary and as cullcheck scene JSON, both in
// scene-local coordinates, z up) and lists every object with its id, name, kind and bounds, so a
// subject can cull boxes without loading any file. M and P are core/camera_matrices.hpp's view
// and projection (row-major, OpenGL convention; P is null for 360-degree cameras).
#pragma once

#include <cstddef>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "core/camera.hpp"
#include "core/scene.hpp"

namespace cullcheck::protocol {

inline constexpr int kVersion = 1;

// The files a subject loads (absolute paths; glb may be empty when no glTF was written).
struct SceneFiles {
  std::string glb;
  std::string json;
};

nlohmann::json hello(const Scene& scene, const SceneFiles& files, std::size_t frames);
// One frame's request as one line (with its newline).
std::string frame_line(std::size_t frame, double time_seconds, const Camera& camera);
std::string bye_line();

// What a subject claims about its answers: conservative (it never culls what is visible), or
// approximate within a budget of misdrawn pixels per frame (oracle/pixel_oracle.hpp).
struct Claim {
  bool conservative = true;
  std::optional<std::uint64_t> pixel_error_budget;  // approximate subjects only
};

struct Ready {
  std::string name;
  Claim claim;
  bool perspective = true, orthographic = false, omnidirectional = false;  // cameras it takes
};

// Problems in a parsed message, or "" when it is well formed. `frame` is the frame expected;
// `known` the scene's ids, sorted. parse_* throw SubjectError (subjects/subject_error.hpp)
// naming `subject` and the frame.
Ready parse_ready(const std::string& line, const std::string& subject);
// Reads a claim ("conservative", or "approximate" with a budget) from a ready-like object; the
// recorded-PVS file's header uses it too.
Claim parse_claim(const nlohmann::json& message, const std::string& subject, std::int64_t frame);

struct Visible {
  std::size_t frame = 0;
  std::vector<ObjectId> ids;         // sorted, unique
  std::optional<double> cull_ms;     // the subject's own timing, if it sent one
};
Visible parse_visible(const std::string& line, const std::string& subject, std::size_t frame,
                      const std::vector<ObjectId>& known);
// The same from a parsed object (the recorded-PVS file reads lines itself).
Visible parse_visible(const nlohmann::json& message, const std::string& subject, std::size_t frame,
                      const std::vector<ObjectId>& known);

}  // namespace cullcheck::protocol
