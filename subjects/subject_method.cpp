#include "subjects/subject_method.hpp"

#include <algorithm>
#include <chrono>

#include "core/elapsed.hpp"
#include "core/utf8.hpp"
#include <iterator>

namespace cullcheck {
namespace {

using Clock = std::chrono::steady_clock;
using Kind = SubjectError::Kind;

std::string seconds_text(double s) {
  char text[32];
  std::snprintf(text, sizeof text, "%g s", s);
  return text;
}

}  // namespace

std::string program_name(const std::string& command) {
  // The first word that is not an interpreter (python3 script.py names the script).
  static const char* interpreters[] = {"python", "python3", "sh", "bash", "node", "env", "exec", "nice", "timeout"};
  std::size_t begin = 0;
  for (;;) {
    begin = command.find_first_not_of(" \t", begin);
    if (begin == std::string::npos) return "subject";
    const std::size_t end = command.find_first_of(" \t", begin);
    std::string word = command.substr(begin, end == std::string::npos ? std::string::npos : end - begin);
    if (const std::size_t slash = word.rfind('/'); slash != std::string::npos) word = word.substr(slash + 1);
    const bool interpreter = std::find(std::begin(interpreters), std::end(interpreters), word) != std::end(interpreters);
    if (!interpreter || end == std::string::npos) return word.empty() ? "subject" : word;
    begin = end;
  }
}

SubjectMethod::SubjectMethod(const Scene& scene, SubjectOptions options, std::size_t frames)
    : scene_(scene), options_(std::move(options)), known_(scene.ids()) {
  const auto start = Clock::now();
  display_name_ = options_.name.empty() ? program_name(options_.command) : options_.name;
  try {
    process_ = std::make_unique<ChildProcess>(ChildProcess::Options{options_.command, options_.stderr_path});
  } catch (const std::exception& e) {
    throw SubjectError(Kind::failed_to_start, label(), SubjectError::kHandshake, e.what());
  }
  const std::string hello = protocol::hello(scene, options_.files, frames).dump() + "\n";
  if (process_->write(hello, options_.hello_timeout) != ChildProcess::Io::ok)
    fail(Kind::crashed, SubjectError::kHandshake, "it did not read the hello");
  const std::string reply = read_reply(SubjectError::kHandshake, options_.hello_timeout, "its ready message");
  try {
    ready_ = protocol::parse_ready(reply, label());
  } catch (const SubjectError& e) {
    fail(e.kind(), e.frame(), e.problem());
  }
  if (options_.name.empty() && !ready_.name.empty()) display_name_ = ready_.name;
  timing_.hello_ms = ms_since(start);
}

SubjectMethod::~SubjectMethod() {
  if (!process_) return;
  if (!said_bye_ && !process_->exited()) process_->write(protocol::bye_line(), 1.0);
  process_->finish(options_.exit_timeout);
}

std::string SubjectMethod::label() const { return "subject '" + display_name_ + "'"; }

void SubjectMethod::fail(Kind kind, std::int64_t frame, const std::string& problem) {
  std::string text = problem;
  if (kind == Kind::crashed || kind == Kind::timed_out) {
    if (kind == Kind::timed_out) process_->kill_group();
    process_->finish(0.5);
    if (kind == Kind::crashed) text += " (" + process_->exit_description() + ")";
  } else {
    process_->kill_group();  // a subject that lies is not asked again
  }
  std::string tail = valid_utf8(process_->stderr_tail(600));
  if (!tail.empty()) {
    while (!tail.empty() && (tail.back() == '\n' || tail.back() == '\r')) tail.pop_back();
    text += "; its stderr ends: " + tail;
  }
  said_bye_ = true;
  throw SubjectError(kind, label(), frame, text);
}

std::string SubjectMethod::read_reply(std::int64_t frame, double timeout, const char* awaiting) {
  std::string line;
  switch (process_->read_line(line, timeout, options_.max_line_bytes)) {
    case ChildProcess::Io::ok:
      return line;
    case ChildProcess::Io::timeout:
      fail(Kind::timed_out, frame, std::string("no answer within ") + seconds_text(timeout) + " (awaiting " + awaiting + ")");
    case ChildProcess::Io::closed:
      fail(Kind::crashed, frame, std::string("closed its output before ") + awaiting);
    case ChildProcess::Io::too_long:
      fail(Kind::garbage, frame, "sent a line longer than " + std::to_string(options_.max_line_bytes) + " bytes");
  }
  fail(Kind::protocol, frame, "unreachable");
}

std::string SubjectMethod::unsupported_camera(const Camera& camera) const {
  const bool ok = camera.orthographic() ? ready_.orthographic : camera.omnidirectional() ? ready_.omnidirectional : ready_.perspective;
  if (ok) return "";
  const char* kind = camera.orthographic() ? "orthographic" : camera.omnidirectional() ? "omnidirectional" : "perspective";
  return std::string(kind) + " camera: " + label() + " did not list \"" + kind + "\" in its ready message's \"projections\"";
}

void SubjectMethod::set_frame(std::size_t frame, double time_seconds) {
  frame_ = frame;
  time_ = time_seconds;
}

CullResult SubjectMethod::cull(const Camera& camera) {
  const auto start = Clock::now();
  const auto at = static_cast<std::int64_t>(frame_);
  if (process_->write(protocol::frame_line(frame_, time_, camera), options_.frame_timeout) != ChildProcess::Io::ok)
    fail(process_->exited() ? Kind::crashed : Kind::timed_out, at, "it did not read the frame request");
  const std::string reply = read_reply(at, options_.frame_timeout, "the visible ids");
  protocol::Visible visible;
  try {
    visible = protocol::parse_visible(reply, label(), frame_, known_);
  } catch (const SubjectError& e) {
    fail(e.kind(), e.frame(), e.problem());
  }
  const double round_trip = ms_since(start);
  CullResult result;
  result.pvs = visible.ids;
  result.stats.cull_ms = visible.cull_ms.value_or(round_trip);
  result.stats.protocol_ms = visible.cull_ms ? std::max(0.0, round_trip - *visible.cull_ms) : round_trip;
  ++timing_.frames;
  timing_.round_trip_ms += round_trip;
  timing_.subject_cull_ms += visible.cull_ms.value_or(0.0);
  timing_.protocol_ms += result.stats.protocol_ms;
  timing_.frames_without_timing += visible.cull_ms ? 0 : 1;
  ++frame_;
  return result;
}

}  // namespace cullcheck
