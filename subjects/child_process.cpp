#include "subjects/child_process.hpp"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <fstream>
#include <mutex>
#include <stdexcept>
#include <thread>

namespace cullcheck {
namespace {

using Clock = std::chrono::steady_clock;

[[noreturn]] void fail(const char* what) { throw std::runtime_error(std::string(what) + ": " + std::strerror(errno)); }

int remaining_ms(Clock::time_point deadline) {
  const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now()).count();
  return left <= 0 ? 0 : static_cast<int>(std::min<long long>(left, 1 << 30));
}

Clock::time_point deadline_after(double seconds) {
  return Clock::now() + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(seconds));
}

}  // namespace

ChildProcess::ChildProcess(const Options& options) : options_(options) {
  static std::once_flag ignore_sigpipe;
  std::call_once(ignore_sigpipe, [] { ::signal(SIGPIPE, SIG_IGN); });
  int in[2], out[2];
  if (::pipe2(in, O_CLOEXEC) != 0) fail("pipe");
  if (::pipe2(out, O_CLOEXEC) != 0) {
    ::close(in[0]), ::close(in[1]);
    fail("pipe");
  }
  int err = -1;
  if (!options.stderr_path.empty()) {
    err = ::open(options.stderr_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    if (err < 0) {
      ::close(in[0]), ::close(in[1]), ::close(out[0]), ::close(out[1]);
      fail(("cannot open " + options.stderr_path).c_str());
    }
  }
  pid_ = ::fork();
  if (pid_ < 0) {
    ::close(in[0]), ::close(in[1]), ::close(out[0]), ::close(out[1]);
    if (err >= 0) ::close(err);
    fail("fork");
  }
  if (pid_ == 0) {  // the child: only async-signal-safe calls until exec
    ::setpgid(0, 0);
    ::signal(SIGPIPE, SIG_DFL);
    ::dup2(in[0], STDIN_FILENO);
    ::dup2(out[1], STDOUT_FILENO);
    if (err >= 0) ::dup2(err, STDERR_FILENO);
    ::execl("/bin/sh", "sh", "-c", options.command.c_str(), static_cast<char*>(nullptr));
    ::_exit(127);
  }
  ::setpgid(pid_, pid_);  // also here, so kill_group works even before the child ran setpgid
  ::close(in[0]);
  ::close(out[1]);
  if (err >= 0) ::close(err);
  to_child_ = in[1];
  from_child_ = out[0];
  ::fcntl(to_child_, F_SETFL, ::fcntl(to_child_, F_GETFL) | O_NONBLOCK);
  ::fcntl(from_child_, F_SETFL, ::fcntl(from_child_, F_GETFL) | O_NONBLOCK);
}

ChildProcess::~ChildProcess() {
  close_input();
  if (from_child_ >= 0) ::close(from_child_);
  if (!exited()) {
    kill_group();
    if (!reaped_ && ::waitpid(pid_, &status_, 0) == pid_) reaped_ = true;
  }
}

ChildProcess::Io ChildProcess::write(const std::string& text, double timeout_seconds) {
  if (to_child_ < 0) return Io::closed;
  const auto deadline = deadline_after(timeout_seconds);
  std::size_t done = 0;
  while (done < text.size()) {
    const ssize_t n = ::write(to_child_, text.data() + done, text.size() - done);
    if (n > 0) {
      done += static_cast<std::size_t>(n);
      continue;
    }
    if (n < 0 && errno == EINTR) continue;
    if (n < 0 && errno == EPIPE) return Io::closed;
    if (n < 0 && errno != EAGAIN && errno != EWOULDBLOCK) fail("write to subject");
    pollfd p{to_child_, POLLOUT, 0};
    const int ms = remaining_ms(deadline);
    if (ms == 0) return Io::timeout;
    if (::poll(&p, 1, ms) < 0 && errno != EINTR) fail("poll");
    if (p.revents & (POLLERR | POLLHUP)) return Io::closed;
  }
  return Io::ok;
}

ChildProcess::Io ChildProcess::read_line(std::string& line, double timeout_seconds, std::size_t max_bytes) {
  const auto deadline = deadline_after(timeout_seconds);
  std::size_t scanned = 0;
  for (;;) {
    if (const std::size_t nl = buffer_.find('\n', scanned); nl != std::string::npos) {
      if (nl > max_bytes) return Io::too_long;
      line.assign(buffer_, 0, nl);
      buffer_.erase(0, nl + 1);
      return Io::ok;
    }
    scanned = buffer_.size();
    if (buffer_.size() > max_bytes) return Io::too_long;
    if (from_child_ < 0) return Io::closed;
    char chunk[1 << 16];
    const ssize_t n = ::read(from_child_, chunk, sizeof chunk);
    if (n > 0) {
      buffer_.append(chunk, static_cast<std::size_t>(n));
      continue;
    }
    if (n == 0) {  // end of file: a last line without a newline is still a line
      ::close(from_child_);
      from_child_ = -1;
      if (!buffer_.empty()) {
        line.swap(buffer_);
        buffer_.clear();
        return Io::ok;
      }
      return Io::closed;
    }
    if (errno == EINTR) continue;
    if (errno != EAGAIN && errno != EWOULDBLOCK) fail("read from subject");
    pollfd p{from_child_, POLLIN, 0};
    const int ms = remaining_ms(deadline);
    if (ms == 0) return Io::timeout;
    if (::poll(&p, 1, ms) < 0 && errno != EINTR) fail("poll");
  }
}

void ChildProcess::close_input() {
  if (to_child_ >= 0) ::close(to_child_);
  to_child_ = -1;
}

bool ChildProcess::exited() {
  if (reaped_) return true;
  if (pid_ <= 0) return true;
  const pid_t r = ::waitpid(pid_, &status_, WNOHANG);
  if (r == pid_) reaped_ = true;
  return reaped_;
}

std::string ChildProcess::exit_description() const {
  if (!reaped_) return "still running";
  if (WIFEXITED(status_)) {
    const int code = WEXITSTATUS(status_);
    if (code == 127) return "exited with status 127 (command not found?)";
    // A shell reports a child killed by signal N as status 128 + N.
    if (code > 128 && code < 128 + 65)
      return "exited with status " + std::to_string(code) + " (signal " + std::to_string(code - 128) + ", " +
             ::strsignal(code - 128) + ", in the program the shell ran)";
    return "exited with status " + std::to_string(code);
  }
  if (WIFSIGNALED(status_)) {
    const int sig = WTERMSIG(status_);
    return "killed by signal " + std::to_string(sig) + " (" + ::strsignal(sig) + ")";
  }
  return "ended with wait status " + std::to_string(status_);
}

void ChildProcess::finish(double timeout_seconds) {
  close_input();
  const auto deadline = deadline_after(timeout_seconds);
  while (!exited()) {
    if (Clock::now() >= deadline) {
      kill_group();
      if (::waitpid(pid_, &status_, 0) == pid_) reaped_ = true;
      return;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
}

void ChildProcess::kill_group() {
  if (pid_ > 0 && !reaped_) {
    ::kill(-pid_, SIGKILL);
    ::kill(pid_, SIGKILL);
  }
}

std::string ChildProcess::stderr_tail(std::size_t bytes) const {
  if (options_.stderr_path.empty()) return "";
  std::ifstream in(options_.stderr_path, std::ios::binary | std::ios::ate);
  if (!in) return "";
  const std::streamoff size = in.tellg();
  const std::streamoff start = size > static_cast<std::streamoff>(bytes) ? size - static_cast<std::streamoff>(bytes) : 0;
  in.seekg(start);
  std::string tail(static_cast<std::size_t>(size - start), '\0');
  in.read(tail.data(), static_cast<std::streamsize>(tail.size()));
  return tail;
}

}  // namespace cullcheck
