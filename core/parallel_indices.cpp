#include "core/parallel_indices.hpp"

#include <algorithm>
#include <atomic>
#include <exception>
#include <thread>
#include <vector>

namespace cullcheck {

unsigned thread_count(unsigned threads, std::size_t count) {
  const unsigned cores = std::max(1u, std::thread::hardware_concurrency());
  return static_cast<unsigned>(std::max<std::size_t>(1, std::min<std::size_t>(threads == 0 ? cores : threads, count)));
}

void for_each_index(std::size_t count, unsigned threads, const std::function<std::function<void(std::size_t)>()>& make_worker) {
  if (count == 0) return;
  std::vector<std::exception_ptr> failures(count);
  std::atomic<std::size_t> next{0};
  auto run = [&] {
    std::function<void(std::size_t)> work;
    try {
      work = make_worker();
    } catch (...) {  // a worker that cannot be made fails the first index it would have taken
      const std::size_t i = next++;
      if (i < count) failures[i] = std::current_exception();
      return;
    }
    for (std::size_t i = next++; i < count; i = next++) {
      try {
        work(i);
      } catch (...) {
        failures[i] = std::current_exception();
      }
    }
  };
  std::vector<std::thread> pool;
  for (unsigned t = 1; t < thread_count(threads, count); ++t) pool.emplace_back(run);
  run();
  for (std::thread& t : pool) t.join();
  for (const std::exception_ptr& e : failures)
    if (e) std::rethrow_exception(e);
}

}  // namespace cullcheck
