// Progress of a long run on stderr (issue 12): what stage, how far, the time left, one line
// rewritten in place. Shown only when stderr is a terminal (CI logs stay clean) and never with
// --quiet; a stage that ends within its first 2 seconds shows nothing. Nothing a run computes or
// writes depends on it. CULLCHECK_PROGRESS=always|never overrides the terminal test (tests).
#pragma once

#include <atomic>
#include <chrono>
#include <cstddef>
#include <mutex>
#include <string>

namespace cullcheck {

class Progress {
 public:
  enum class Mode { automatic, never, always };
  // Every Progress from now on: `never` is --quiet.
  static void set_mode(Mode mode);
  // Whether progress lines are written (the mode, the environment, whether stderr is a terminal).
  static bool shown();

  // A stage of `total` steps counted in `unit` ("frames", "cells"); total 0 when unknown.
  Progress(std::string stage, std::size_t total, std::string unit);
  ~Progress();  // clears the line when anything was shown
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;

  // Thread-safe: `steps` more done. Writes at most 4 lines a second.
  void advance(std::size_t steps = 1);

  // The line shown after `done` of `total` steps in `elapsed_seconds` (tests pin its text).
  static std::string line(const std::string& stage, std::size_t done, std::size_t total, const std::string& unit,
                          double elapsed_seconds);

 private:
  std::string stage_, unit_;
  std::size_t total_;
  std::atomic<std::size_t> done_{0};
  std::chrono::steady_clock::time_point start_, last_shown_;
  std::mutex print_;
  bool enabled_ = false, printed_ = false;
};

}  // namespace cullcheck
