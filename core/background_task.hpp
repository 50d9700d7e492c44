// One background thread that runs one task at a time, for work taken off a query's critical
// path (the guarded ΔH's next certificate). Starting a thread per task (std::async) cost the
// query that started it tens of microseconds; this thread is started once and waits between
// tasks.
#pragma once

#include <condition_variable>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>

namespace cullcheck {

class BackgroundTask {
 public:
  BackgroundTask() = default;
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

 private:
  void loop();

  std::mutex mutex_;
  std::condition_variable wake_, finished_;
  std::function<void()> task_;  // set while a task waits for the thread or runs
  bool running_ = false;        // task_ holds a task not yet finished
  bool stop_ = false;
  std::exception_ptr error_;
  bool pending_ = false;  // the caller's side: started, not yet waited for
  std::thread thread_;    // declared last: the members above outlive it
};

}  // namespace cullcheck
