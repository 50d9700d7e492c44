// What went wrong with an outside culling system under test (a subject). A subject is bad input
// like a malformed scene file (README "Exit codes": 2): it may crash, hang, print garbage,
// answer the wrong frame or name objects the scene does not have. Every such failure names the
// subject, the frame (or the handshake) and what was wrong.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>

namespace cullcheck {

class SubjectError : public std::runtime_error {
 public:
  enum class Kind {
    failed_to_start,  // the program could not be started
    crashed,          // exited or was killed by a signal while an answer was due
    timed_out,        // no answer within the timeout
    garbage,          // a line that is not the JSON message expected
    wrong_frame,      // an answer for another frame
    unknown_id,       // an id the scene does not have
    protocol,         // anything else the protocol forbids (version, missing fields, missing frames)
  };
  static constexpr std::int64_t kHandshake = -1;  // `frame` of a failure before the first frame

  SubjectError(Kind kind, std::string subject, std::int64_t frame, const std::string& problem)
      : std::runtime_error(subject + (frame == kHandshake ? " during the handshake" : " at frame " + std::to_string(frame)) +
                           ": " + kind_name(kind) + ": " + problem),
        kind_(kind),
        subject_(std::move(subject)),
        frame_(frame),
        problem_(problem) {}

  Kind kind() const { return kind_; }
  const std::string& subject() const { return subject_; }
  std::int64_t frame() const { return frame_; }
  const std::string& problem() const { return problem_; }

  static const char* kind_name(Kind k) {
    switch (k) {
      case Kind::failed_to_start: return "failed to start";
      case Kind::crashed: return "crashed";
      case Kind::timed_out: return "timed out";
      case Kind::garbage: return "garbage";
      case Kind::wrong_frame: return "wrong frame";
      case Kind::unknown_id: return "unknown id";
      case Kind::protocol: return "protocol violation";
    }
    return "?";
  }

 private:
  Kind kind_;
  std::string subject_;
  std::int64_t frame_;
  std::string problem_;
};

}  // namespace cullcheck
