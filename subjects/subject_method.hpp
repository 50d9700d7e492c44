// An outside culling system as a CullingMethod (engine/method.hpp): a program started once per
// scene and asked frame by frame over the subject protocol (subjects/protocol.hpp). It is held to
// the oracle, the fuzzer, the claims ledger and the report like every built-in method.
//
// Its answers are input, and may be bad: a crash, a hang (per-frame timeout), garbage, the wrong
// frame or an unknown id raises SubjectError naming the frame and what was wrong, and the
// program is killed. Time in the protocol is measured per frame: the round trip less the
// subject's own cull_ms (the whole round trip when it sends none).
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "engine/method.hpp"
#include "subjects/child_process.hpp"
#include "subjects/protocol.hpp"
#include "subjects/subject_error.hpp"

namespace cullcheck {

struct SubjectOptions {
  std::string command;              // run by /bin/sh -c
  std::string name;                 // shown in reports; default: the ready message's name, else the program
  protocol::SceneFiles files;       // what the hello names (the caller writes them)
  std::string stderr_path;          // where its stderr goes (empty: inherited)
  double hello_timeout = 60.0;      // seconds to load the scene and answer the hello
  double frame_timeout = 10.0;      // seconds per frame
  double exit_timeout = 5.0;        // seconds to exit after bye before it is killed
  std::size_t max_line_bytes = std::size_t(1) << 28;
};

// Per-run totals of where a subject's frames spent their time.
struct ProtocolTiming {
  std::size_t frames = 0;
  double round_trip_ms = 0.0;      // request written to answer parsed, summed
  double subject_cull_ms = 0.0;    // what the subject reported, summed
  double protocol_ms = 0.0;        // round trip less the subject's cull_ms
  std::size_t frames_without_timing = 0;  // answers without cull_ms
  double hello_ms = 0.0;           // starting it, the hello and its ready
};

class SubjectMethod final : public CullingMethod {
 public:
  // Starts the program and performs the handshake; throws SubjectError on failure. `scene`
  // must outlive the method.
  SubjectMethod(const Scene& scene, SubjectOptions options, std::size_t frames);
  ~SubjectMethod() override;  // says bye and waits (exit_timeout) for it to exit, then kills it

  std::string name() const override { return "subject:" + display_name_; }
  bool claims_conservative() const override { return ready_.claim.conservative; }
  std::optional<std::uint64_t> pixel_error_budget() const override { return ready_.claim.pixel_error_budget; }
  std::string unsupported_camera(const Camera& camera) const override;
  void set_frame(std::size_t frame, double time_seconds) override;
  CullResult cull(const Camera& camera) override;

  const SubjectOptions& options() const { return options_; }
  const protocol::Ready& ready() const { return ready_; }
  const ProtocolTiming& timing() const { return timing_; }

 private:
  [[noreturn]] void fail(SubjectError::Kind kind, std::int64_t frame, const std::string& problem);
  std::string read_reply(std::int64_t frame, double timeout, const char* awaiting);
  std::string label() const;  // "subject 'NAME'"

  const Scene& scene_;
  SubjectOptions options_;
  std::vector<ObjectId> known_;
  std::unique_ptr<ChildProcess> process_;
  protocol::Ready ready_;
  std::string display_name_;
  std::size_t frame_ = 0;
  double time_ = 0.0;
  bool said_bye_ = false;
  ProtocolTiming timing_;
};

// The program's name from a command line: the last path component of its first word.
std::string program_name(const std::string& command);

}  // namespace cullcheck
