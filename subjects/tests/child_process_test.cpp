// ChildProcess (subjects/child_process.hpp) with `sh -c` one-liners: lines both ways, deadlines
// that hold, exits and signals described, over-long lines, writes to a program that is gone, and
// a destructor that kills what will not exit.
//
// No upper bounds on elapsed time (they fail on a loaded machine): a deadline is shown to hold by
// what it returns against a program that would answer otherwise only much later (Io::timeout,
// not the Io::closed of a 30 s sleep that ended), and a kill by the exit it causes against a
// program that never ends by itself (a test that hangs instead fails at CTest's timeout). Lower
// bounds stay: a deadline that fired early would pass under any load, and the clock cannot run
// fast.
#include <gtest/gtest.h>

#include <signal.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <fstream>
#include <string>
#include <thread>

#include "core/elapsed.hpp"
#include "subjects/child_process.hpp"

namespace cullcheck {
namespace {

using Io = ChildProcess::Io;
using Clock = std::chrono::steady_clock;

ChildProcess::Options sh(const std::string& command) { return {command, ""}; }

// Waits (up to 5 s) for the program to exit on its own.
bool wait_exit(ChildProcess& p) {
  const auto start = Clock::now();
  while (!p.exited()) {
    if (seconds_since(start) > 5) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  return true;
}

TEST(ChildProcess, EchoesALineBack) {
  ChildProcess p(sh(R"(read l; echo "$l")"));
  ASSERT_EQ(p.write("hello world\n", 5), Io::ok);
  std::string line;
  ASSERT_EQ(p.read_line(line, 5, 1000), Io::ok);
  EXPECT_EQ(line, "hello world");  // without its newline
  // It exits after one line: end of file.
  EXPECT_EQ(p.read_line(line, 5, 1000), Io::closed);
  ASSERT_TRUE(wait_exit(p));
  EXPECT_EQ(p.exit_description(), "exited with status 0");
}

TEST(ChildProcess, SeveralLinesInOneReadComeOutOneByOne) {
  ChildProcess p(sh(R"(printf 'one\ntwo\nthree')"));
  std::string line;
  ASSERT_EQ(p.read_line(line, 5, 1000), Io::ok);
  EXPECT_EQ(line, "one");
  ASSERT_EQ(p.read_line(line, 5, 1000), Io::ok);
  EXPECT_EQ(line, "two");
  // A last line without a newline is still a line, then end of file.
  ASSERT_EQ(p.read_line(line, 5, 1000), Io::ok);
  EXPECT_EQ(line, "three");
  EXPECT_EQ(p.read_line(line, 5, 1000), Io::closed);
}

TEST(ChildProcess, ReadTimesOutAtItsDeadline) {
  ChildProcess p(sh("sleep 30"));
  std::string line;
  const auto before = Clock::now();
  EXPECT_EQ(p.read_line(line, 0.2, 1000), Io::timeout);  // not Io::closed, 30 s later
  EXPECT_GE(seconds_since(before), 0.19);                 // and not early
  EXPECT_FALSE(p.exited());
  EXPECT_EQ(p.exit_description(), "still running");
}  // the destructor kills `sleep 30`

TEST(ChildProcess, ExitStatusIsDescribed) {
  ChildProcess p(sh("exit 3"));
  std::string line;
  EXPECT_EQ(p.read_line(line, 5, 1000), Io::closed);
  ASSERT_TRUE(wait_exit(p));
  EXPECT_EQ(p.exit_description(), "exited with status 3");
}

TEST(ChildProcess, CommandNotFoundIsDescribed) {
  ChildProcess p(sh("/nonexistent/cullcheck-subject 2>/dev/null"));
  p.finish(5);
  EXPECT_EQ(p.exit_description(), "exited with status 127 (command not found?)");
}

TEST(ChildProcess, SignalIsDescribed) {
  // The shell kills itself: the wait status is "killed by signal 11".
  ChildProcess p(sh("ulimit -c 0; kill -SEGV $$"));
  p.finish(5);
  ASSERT_TRUE(p.exited());
  EXPECT_EQ(p.exit_description(), "killed by signal 11 (" + std::string(::strsignal(SIGSEGV)) + ")");
  EXPECT_NE(p.exit_description().find("Segmentation fault"), std::string::npos);
}

TEST(ChildProcess, SignalOfAProgramTheShellRanIsDescribed) {
  // The shell's child is killed by SIGSEGV; the shell exits with 128 + 11 = 139.
  ChildProcess p(sh(R"(ulimit -c 0; sh -c 'kill -SEGV $$'; exit $?)"));
  p.finish(5);
  EXPECT_EQ(p.exit_description(),
            "exited with status 139 (signal 11, " + std::string(::strsignal(SIGSEGV)) + ", in the program the shell ran)");
}

TEST(ChildProcess, LineWithoutNewlineBeyondMaxBytesIsTooLong) {
  // 100 bytes and no newline, then silence: after max_bytes = 10 it is too long (not a timeout,
  // which is what waiting for the newline would give, after 30 s).
  ChildProcess p(sh("printf '%0100d' 0; sleep 30"));
  std::string line;
  EXPECT_EQ(p.read_line(line, 30, 10), Io::too_long);
}

TEST(ChildProcess, ShortLinesWithinMaxBytesAreRead) {
  ChildProcess p(sh("echo 0123456789"));  // 10 bytes and a newline, max_bytes 10
  std::string line;
  EXPECT_EQ(p.read_line(line, 5, 10), Io::ok);
  EXPECT_EQ(line, "0123456789");
}

// Regression test of a bug it found, since fixed (subjects/child_process.cpp, ChildProcess::read_line): the header promises `too_long` "when
// no newline came within `max_bytes`", and SubjectMethod reports too_long as "sent a line longer
// than max_line_bytes bytes"; but read_line looks for a newline in its buffer before it checks the
// buffer's size, so a line longer than max_bytes whose newline arrives in the same read(2) chunk
// (up to 64 KiB) is returned as Io::ok. Here a 100-byte line with max_bytes = 10 is returned whole.
TEST(ChildProcess, LineWithNewlineBeyondMaxBytesIsTooLong) {
  ChildProcess p(sh("printf '%0100d\\n' 0"));
  std::string line;
  EXPECT_EQ(p.read_line(line, 5, 10), Io::too_long) << "returned a line of " << line.size() << " bytes";
}

TEST(ChildProcess, WritingToAProgramThatExitedIsClosed) {
  // SIGPIPE is ignored, so the write fails with EPIPE and returns `closed`; this test process
  // would die of SIGPIPE otherwise.
  ChildProcess p(sh("exit 0"));
  ASSERT_TRUE(wait_exit(p));
  EXPECT_EQ(p.write("hello\n", 1), Io::closed);
  EXPECT_EQ(p.write(std::string(1 << 20, 'x'), 1), Io::closed);
  // After close_input there is nothing to write to either.
  p.close_input();
  EXPECT_EQ(p.write("hello\n", 1), Io::closed);
}

TEST(ChildProcess, WritingToAProgramThatDoesNotReadTimesOut) {
  // 1 MiB into a pipe (64 KiB buffer) that nobody reads: the deadline holds (Io::timeout, not
  // the Io::closed of a write that blocked until the program exited 30 s later).
  ChildProcess p(sh("sleep 30"));
  const auto start = Clock::now();
  EXPECT_EQ(p.write(std::string(1 << 20, 'x'), 0.2), Io::timeout);
  EXPECT_GE(seconds_since(start), 0.19);
}

TEST(ChildProcess, StderrGoesToItsFile) {
  const std::string path = ::testing::TempDir() + "child_process_stderr.txt";
  {
    ChildProcess p({"echo to-stderr >&2; exit 1", path});
    p.finish(5);
    EXPECT_EQ(p.exit_description(), "exited with status 1");
    EXPECT_EQ(p.stderr_tail(), "to-stderr\n");
    EXPECT_EQ(p.stderr_tail(4), "err\n");  // the last 4 bytes
  }
  std::remove(path.c_str());
}

// Whether process `pid` is gone (or only a zombie waiting for its new parent to reap it).
bool gone(pid_t pid) {
  if (::kill(pid, 0) != 0 && errno == ESRCH) return true;
  std::ifstream stat("/proc/" + std::to_string(pid) + "/stat");
  std::string text;
  std::getline(stat, text);
  const std::size_t paren = text.rfind(')');
  return paren != std::string::npos && paren + 2 < text.size() && text[paren + 2] == 'Z';
}

TEST(ChildProcess, DestructorKillsAProgramThatIgnoresEndOfInput) {
  // The shell ignores end of input and SIGTERM, and starts a background sleep in its process
  // group; the destructor must kill both (else it never returns: the loop does not end).
  pid_t grandchild = -1;
  {
    ChildProcess p(sh("trap '' TERM; sleep 30 & echo $!; while :; do sleep 1; done"));
    std::string line;
    ASSERT_EQ(p.read_line(line, 5, 100), Io::ok);
    grandchild = static_cast<pid_t>(std::stol(line));
    p.close_input();
    EXPECT_FALSE(p.exited());
  }
  ASSERT_GT(grandchild, 0);
  // SIGKILL went to the group; give the kernel time to deliver it even on a loaded machine (the
  // sleep it kills would last 30 s).
  const auto waiting = Clock::now();
  while (!gone(grandchild) && seconds_since(waiting) < 20) std::this_thread::sleep_for(std::chrono::milliseconds(10));
  EXPECT_TRUE(gone(grandchild)) << "the background sleep " << grandchild << " survived";
}

TEST(ChildProcess, FinishKillsAfterItsTimeout) {
  ChildProcess p(sh("trap '' TERM; while :; do sleep 1; done"));
  const auto start = Clock::now();
  p.finish(0.2);
  EXPECT_GE(seconds_since(start), 0.19);  // it was given its time
  ASSERT_TRUE(p.exited());                // and then killed: the loop never ends by itself
  EXPECT_EQ(p.exit_description(), "killed by signal 9 (" + std::string(::strsignal(SIGKILL)) + ")");
}

}  // namespace
}  // namespace cullcheck
