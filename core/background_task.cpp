#include "core/background_task.hpp"

#include <algorithm>
#include <stdexcept>
#include <utility>

namespace cullcheck {

BackgroundTask::~BackgroundTask() {
  if (!thread_.joinable()) return;
  bool napping;
  {
    std::unique_lock lock(mutex_);
    finished_.wait(lock, [&] { return !running_; });
    stop_ = true;
    poked_.store(true, std::memory_order_release);
    napping = napping_;
  }
  if (!napping) wake_.notify_one();
  thread_.join();
}

void BackgroundTask::start(std::function<void()> task) {
  if (pending_) throw std::logic_error("BackgroundTask::start: the last task was not waited for");
  // First, so that a thread that cannot be started (std::system_error) leaves nothing pending.
  if (!thread_.joinable()) thread_ = std::thread([this] { loop(); });
  bool napping;
  {
    const std::lock_guard lock(mutex_);
    task_ = std::move(task);
    error_ = nullptr;
    running_ = true;
    poked_.store(true, std::memory_order_release);
    // napping_ is only changed under the mutex: a napping thread will see poked_ before it
    // could park, and a thread that stopped napping waits on wake_ for running_.
    napping = napping_;
  }
  if (!napping) {
    ++wakes_;
    wake_.notify_one();
  }
  pending_ = true;
}

void BackgroundTask::wait() {
  if (!pending_) return;
  std::exception_ptr error;
  {
    std::unique_lock lock(mutex_);
    finished_.wait(lock, [&] { return !running_; });
    error = std::exchange(error_, nullptr);
  }
  pending_ = false;
  if (error) std::rethrow_exception(error);
}

void BackgroundTask::loop() {
  std::unique_lock lock(mutex_);
  for (;;) {
    if (napping_) {
      lock.unlock();
      // Each nap an eighth of the time since the last task ended (kShortestNap to kLongestNap):
      // a task started soon after is picked up soon, and a long wait wakes the core seldom.
      const auto since = std::chrono::steady_clock::now();
      for (auto now = since; !poked_.load(std::memory_order_acquire) && now - since < nap_window_;
           now = std::chrono::steady_clock::now())
        std::this_thread::sleep_for(std::clamp<std::chrono::steady_clock::duration>((now - since) / 8, kShortestNap, kLongestNap));
      lock.lock();
      napping_ = false;
    }
    wake_.wait(lock, [&] { return stop_ || running_; });
    if (stop_) return;
    poked_.store(false, std::memory_order_relaxed);  // under the mutex, with running_ set
    std::function<void()> task = std::move(task_);
    lock.unlock();
    std::exception_ptr error;
    try {
      task();
    } catch (...) {
      error = std::current_exception();
    }
    lock.lock();
    error_ = error;
    running_ = false;
    napping_ = nap_window_.count() > 0;  // set with running_, so a start() right after wait() sees it
    finished_.notify_one();
  }
}

}  // namespace cullcheck
