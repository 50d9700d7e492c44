// Independent pieces of work numbered 0 .. count - 1 on several threads, with results that do
// not depend on how many: each piece writes its own slot, and the caller folds the slots in order.
#pragma once

#include <cstddef>
#include <functional>

namespace cullcheck {

// min(threads, count) threads (threads 0: every core), at least 1.
unsigned thread_count(unsigned threads, std::size_t count);

// Runs work(i) for every i on thread_count(threads, count) threads, the calling thread among
// them. make_worker() is called once per thread, so a worker may own what a thread must not share
// (a culling method and its buffers). Indices are handed out one at a time. An exception thrown
// for index i is kept; when every thread has ended, the one of the lowest index is rethrown:
// the one a single thread going in order would have raised.
void for_each_index(std::size_t count, unsigned threads, const std::function<std::function<void(std::size_t)>()>& make_worker);

}  // namespace cullcheck
