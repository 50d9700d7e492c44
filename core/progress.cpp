#include "core/progress.hpp"

#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>

namespace cullcheck {
namespace {

std::atomic<Progress::Mode> g_mode{Progress::Mode::automatic};

constexpr double kQuietSeconds = 2.0;      // a stage shorter than this shows nothing
constexpr double kSecondsBetweenLines = 0.25;

std::string duration_text(double seconds) {
  char buffer[32];
  if (seconds < 90) std::snprintf(buffer, sizeof buffer, "%.0f s", seconds);
  else if (seconds < 5400) std::snprintf(buffer, sizeof buffer, "%.0f min", seconds / 60);
  else std::snprintf(buffer, sizeof buffer, "%.1f h", seconds / 3600);
  return buffer;
}

}  // namespace

void Progress::set_mode(Mode mode) { g_mode = mode; }

bool Progress::shown() {
  if (const char* env = std::getenv("CULLCHECK_PROGRESS")) {
    if (std::strcmp(env, "never") == 0) return false;
    if (std::strcmp(env, "always") == 0) return g_mode != Mode::never;
  }
  switch (g_mode.load()) {
    case Mode::never: return false;
    case Mode::always: return true;
    case Mode::automatic: break;
  }
  return ::isatty(STDERR_FILENO) == 1;
}

Progress::Progress(std::string stage, std::size_t total, std::string unit)
    : stage_(std::move(stage)), unit_(std::move(unit)), total_(total), start_(std::chrono::steady_clock::now()),
      last_shown_(start_), enabled_(shown()) {}

Progress::~Progress() {
  if (printed_) std::fputs("\r\033[K", stderr), std::fflush(stderr);
}

std::string Progress::line(const std::string& stage, std::size_t done, std::size_t total, const std::string& unit,
                           double elapsed_seconds) {
  std::string out = stage + ": " + std::to_string(done);
  if (total > 0) {
    char percent[16];
    std::snprintf(percent, sizeof percent, " (%.0f%%)", 100.0 * double(done) / double(total));
    out += "/" + std::to_string(total) + " " + unit + percent + ", " + duration_text(elapsed_seconds);
    if (done > 0 && done < total)
      out += ", about " + duration_text(elapsed_seconds * double(total - done) / double(done)) + " left";
  } else {
    out += " " + unit + ", " + duration_text(elapsed_seconds);
  }
  return out;
}

void Progress::advance(std::size_t steps) {
  const std::size_t done = done_ += steps;
  if (!enabled_) return;
  const auto now = std::chrono::steady_clock::now();
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  if (elapsed < kQuietSeconds) return;
  std::unique_lock lock(print_, std::try_to_lock);  // a busy printer skips: another line comes soon
  if (!lock.owns_lock() || (printed_ && std::chrono::duration<double>(now - last_shown_).count() < kSecondsBetweenLines)) return;
  last_shown_ = now;
  printed_ = true;
  std::fprintf(stderr, "\r\033[K%s", line(stage_, done, total_, unit_, elapsed).c_str());
  std::fflush(stderr);
}

}  // namespace cullcheck
