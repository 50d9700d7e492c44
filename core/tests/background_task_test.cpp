#include "core/background_task.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <stdexcept>
#include <thread>
#include <vector>

namespace cullcheck {
namespace {

TEST(BackgroundTask, RunsEachTaskOnOneOtherThreadInTheOrderStarted) {
  BackgroundTask task;
  std::vector<int> done;
  std::vector<std::thread::id> threads;
  for (int k = 0; k < 5; ++k) {
    task.start([&, k] {
      done.push_back(k);
      threads.push_back(std::this_thread::get_id());
    });
    EXPECT_TRUE(task.pending());
    task.wait();
    EXPECT_FALSE(task.pending());
  }
  EXPECT_EQ(done, (std::vector<int>{0, 1, 2, 3, 4}));
  ASSERT_EQ(threads.size(), 5u);
  for (const std::thread::id id : threads) {
    EXPECT_NE(id, std::this_thread::get_id());
    EXPECT_EQ(id, threads[0]) << "one thread for the object's lifetime";
  }
}

TEST(BackgroundTask, WaitBlocksUntilTheTaskHasFinished) {
  BackgroundTask task;
  std::atomic<bool> finished{false};
  task.start([&] {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    finished = true;
  });
  task.wait();
  EXPECT_TRUE(finished);
}

TEST(BackgroundTask, WaitRethrowsWhatTheTaskThrewAndTheNextTaskRuns) {
  BackgroundTask task;
  task.start([] { throw std::runtime_error("certificate failed"); });
  try {
    task.wait();
    FAIL() << "the task's exception was not rethrown";
  } catch (const std::runtime_error& e) {
    EXPECT_STREQ(e.what(), "certificate failed");
  }
  EXPECT_FALSE(task.pending());
  bool ran = false;
  task.start([&] { ran = true; });
  EXPECT_NO_THROW(task.wait());
  EXPECT_TRUE(ran);
}

TEST(BackgroundTask, StartingWhileATaskIsPendingIsRefused) {
  BackgroundTask task;
  task.start([] {});
  EXPECT_THROW(task.start([] {}), std::logic_error);
  task.wait();
  EXPECT_NO_THROW(task.wait());  // nothing pending: returns
}

TEST(BackgroundTask, DestructionWaitsForARunningTask) {
  std::atomic<bool> finished{false};
  {
    BackgroundTask task;
    task.start([&] {
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
      finished = true;
    });
  }
  EXPECT_TRUE(finished);
}

// A start() soon after the last task finds the thread napping and hands the task over without
// waking it; only the first (the thread starts parked) wakes it.
TEST(BackgroundTask, AStartWhileTheThreadNapsWakesNothing) {
  BackgroundTask task{std::chrono::seconds(10)};
  int ran = 0;
  for (int k = 0; k < 6; ++k) {
    task.start([&] { ++ran; });
    task.wait();
  }
  EXPECT_EQ(ran, 6);
  EXPECT_EQ(task.wakes(), 1u);
}

TEST(BackgroundTask, WithoutANapWindowEveryStartWakesTheParkedThread) {
  BackgroundTask task{std::chrono::microseconds(0)};
  int ran = 0;
  for (int k = 0; k < 4; ++k) {
    task.start([&] { ++ran; });
    task.wait();
  }
  EXPECT_EQ(ran, 4);
  EXPECT_EQ(task.wakes(), 4u);
}

// Past the window the thread parks; a task started then still runs (a lost wake-up would hang
// here), and so does destruction while it naps or is parked.
TEST(BackgroundTask, AfterTheNapWindowATaskStillRuns) {
  BackgroundTask task{std::chrono::milliseconds(1)};
  int ran = 0;
  task.start([&] { ++ran; });
  task.wait();
  std::this_thread::sleep_for(std::chrono::milliseconds(100));
  task.start([&] { ++ran; });
  task.wait();
  EXPECT_EQ(ran, 2);
  EXPECT_GE(task.wakes(), 1u);
}

}  // namespace
}  // namespace cullcheck
