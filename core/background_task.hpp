// One background thread that runs one task at a time, for work taken off a query's critical
// path (the guarded ΔH's next certificate). Starting a thread per task (std::async) cost the
// query that started it tens of microseconds; this thread is started once and waits between
// tasks.
//
// How it waits (issue 17): waking a thread parked on a condition variable cost the caller of
// start() 20-40 µs on this project's 2-core virtual machine (the wake-up of the idle core, paid
// inside notify_one), a third to a half of a re-anchoring ΔH frame. So after each task the
// thread first naps, for up to `nap_window`: each nap lasts an eighth of the time since the task
// ended (50 µs to 2 ms), and between naps it looks for a task, which start() hands over by a
// store, with no system call on the caller's side. A task started soon is picked up soon, and a
// long wait wakes the thread's core at most 500 times a second: with naps of a fixed 50 µs, the
// oracle's rays on both cores ran 8-11% slower beside a napping thread; with these, within noise.
// Only after the window does the thread park on the condition variable, and start() then wakes it
// as before.
#pragma once

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>

namespace cullcheck {

class BackgroundTask {
 public:
  static constexpr std::chrono::microseconds kShortestNap{50}, kLongestNap{2000};
  // A walk re-anchors the guarded ΔH every few frames: about every 0.1-0.2 s at walking speed
  // and 60 frames a second, so a window of a quarter of a second covers it.
  static constexpr std::chrono::milliseconds kNapWindow{250};

  // `nap_window` 0: park after every task (every start() wakes the thread).
  explicit BackgroundTask(std::chrono::microseconds nap_window = kNapWindow) : nap_window_(nap_window) {}
  // Waits for a running task (its exception, if any, is dropped) and joins the thread.
  ~BackgroundTask();
  BackgroundTask(const BackgroundTask&) = delete;
  BackgroundTask& operator=(const BackgroundTask&) = delete;

  // Hands `task` to the thread (started on first use). Only when nothing is pending.
  void start(std::function<void()> task);
  // A task was started and not yet waited for.
  bool pending() const { return pending_; }
  // Blocks until the started task has finished; rethrows what it threw. Nothing pending: returns.
  void wait();
  // How many start() calls had to wake the parked thread (the rest found it napping).
  std::uint64_t wakes() const { return wakes_; }

 private:
  void loop();

  std::chrono::microseconds nap_window_;
  std::mutex mutex_;
  std::condition_variable wake_, finished_;
  std::function<void()> task_;  // set while a task waits for the thread or runs
  bool running_ = false;        // task_ holds a task not yet finished
  bool stop_ = false;
  bool napping_ = false;        // the thread looks for work between naps (start() need not wake it)
  std::atomic<bool> poked_{false};  // running_ or stop_ was set: what a napping thread reads
  std::exception_ptr error_;
  bool pending_ = false;  // the caller's side: started, not yet waited for
  std::uint64_t wakes_ = 0;
  std::thread thread_;    // declared last: the members above outlive it
};

}  // namespace cullcheck
