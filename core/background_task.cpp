#include "core/background_task.hpp"

#include <stdexcept>
#include <utility>

namespace cullcheck {

BackgroundTask::~BackgroundTask() {
  if (!thread_.joinable()) return;
  {
    std::unique_lock lock(mutex_);
    finished_.wait(lock, [&] { return !running_; });
    stop_ = true;
  }
  wake_.notify_one();
  thread_.join();
}

void BackgroundTask::start(std::function<void()> task) {
  if (pending_) throw std::logic_error("BackgroundTask::start: the last task was not waited for");
  // First, so that a thread that cannot be started (std::system_error) leaves nothing pending.
  if (!thread_.joinable()) thread_ = std::thread([this] { loop(); });
  {
    const std::lock_guard lock(mutex_);
    task_ = std::move(task);
    error_ = nullptr;
    running_ = true;
  }
  wake_.notify_one();
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
    wake_.wait(lock, [&] { return stop_ || running_; });
    if (stop_) return;
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
    finished_.notify_one();
  }
}

}  // namespace cullcheck
