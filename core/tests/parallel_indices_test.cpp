// Work on several threads (parallel_indices.hpp): every index done once, by workers made once per
// thread, and the failure of the lowest index raised whatever the number of threads.
#include "core/parallel_indices.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <stdexcept>
#include <string>
#include <vector>

namespace cullcheck {
namespace {

TEST(ParallelIndices, EveryIndexOnceByWorkersMadeOncePerThread) {
  for (unsigned threads : {1u, 2u, 3u, 8u}) {
    std::vector<int> done(100, 0);
    std::atomic<int> workers{0};
    for_each_index(done.size(), threads, [&] {
      ++workers;
      return [&](std::size_t i) { done[i] += static_cast<int>(i) + 1; };
    });
    for (std::size_t i = 0; i < done.size(); ++i) EXPECT_EQ(done[i], static_cast<int>(i) + 1) << threads;
    EXPECT_EQ(workers, static_cast<int>(thread_count(threads, done.size())));
  }
  EXPECT_EQ(thread_count(8, 3), 3u);
  EXPECT_EQ(thread_count(2, 0), 1u);
}

TEST(ParallelIndices, TheLowestIndexFailureIsRaised) {
  for (unsigned threads : {1u, 3u}) {
    try {
      for_each_index(20, threads, [] {
        return [](std::size_t i) {
          if (i == 7 || i == 13) throw std::runtime_error("index " + std::to_string(i));
        };
      });
      ADD_FAILURE() << "nothing raised on " << threads << " threads";
    } catch (const std::runtime_error& e) {
      EXPECT_STREQ(e.what(), "index 7") << threads;
    }
  }
}

}  // namespace
}  // namespace cullcheck
