// An outside program run as a child with its stdin and stdout on pipes, for line-based protocols
// with timeouts (POSIX). The command line is run by /bin/sh -c, in its own process group, so a
// timeout or the destructor can kill it and everything it started. Its stderr goes to a file
// (kept for the error message when it fails) or is inherited.
//
// Nothing here blocks without a deadline: writes and reads wait with poll(2) for at most the
// given seconds. Writing to a program that has exited gives EPIPE, not SIGPIPE (SIGPIPE is set
// to ignored once, process-wide, the first time a ChildProcess starts).
#pragma once

#include <sys/types.h>

#include <cstddef>
#include <optional>
#include <string>

namespace cullcheck {

class ChildProcess {
 public:
  struct Options {
    std::string command;      // run by /bin/sh -c
    std::string stderr_path;  // empty: inherit cullcheck's stderr
  };
  // Throws std::runtime_error (errno text) when the pipes or the fork fail.
  explicit ChildProcess(const Options& options);
  ~ChildProcess();  // closes the pipes, then kills the process group if it has not exited, and reaps it
  ChildProcess(const ChildProcess&) = delete;
  ChildProcess& operator=(const ChildProcess&) = delete;

  enum class Io { ok, timeout, closed, too_long };
  // Writes `text` (a newline is not added). `closed` when the program no longer reads.
  Io write(const std::string& text, double timeout_seconds);
  // Reads one line without its newline into `line`. `closed` at end of file (the program closed
  // stdout or exited), `too_long` when no newline came within `max_bytes`.
  Io read_line(std::string& line, double timeout_seconds, std::size_t max_bytes);
  // Closes the program's stdin (it sees end of file).
  void close_input();

  // Whether it has exited, without waiting; then how, e.g. "exited with status 3" or "killed by
  // signal 11 (Segmentation fault)".
  bool exited();
  std::string exit_description() const;
  int exit_status() const { return status_; }
  // Waits up to `timeout_seconds` for it to exit; kills the process group if it does not.
  void finish(double timeout_seconds);
  void kill_group();
  // The last `bytes` of its stderr file (empty when stderr is inherited).
  std::string stderr_tail(std::size_t bytes = 2000) const;
  pid_t pid() const { return pid_; }

 private:
  Options options_;
  pid_t pid_ = -1;
  int to_child_ = -1, from_child_ = -1;
  std::string buffer_;  // read but not yet returned
  bool reaped_ = false;
  int status_ = 0;
};

}  // namespace cullcheck
