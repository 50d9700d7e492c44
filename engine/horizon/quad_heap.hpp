// A min-heap with four children per node, for the sweeps' queues (horizon_sweep.hpp): half the
// levels of std::priority_queue's binary heap, and a node's four children share a cache line or
// two, so a pop reads fewer lines. The sweeps' orders are strict and total (distance, then kind
// and index, or insertion order), so the pop order is the same as any other heap's: the PVSs do
// not change (issue 17 measured the binary heap at 15% of a VbAoI view cell's time).
#pragma once

#include <cstddef>
#include <vector>

namespace cullcheck {

// `T` must have operator> (a strict order: a > b when b comes out first).
template <class T>
class QuadHeap {
 public:
  bool empty() const { return items_.empty(); }
  std::size_t size() const { return items_.size(); }
  const T& top() const { return items_.front(); }
  void clear() { items_.clear(); }  // keeps the capacity for the next query

  void push(const T& item) {
    std::size_t i = items_.size();
    items_.push_back(item);
    while (i > 0) {
      const std::size_t parent = (i - 1) / 4;
      if (!(items_[parent] > item)) break;
      items_[i] = items_[parent];
      i = parent;
    }
    items_[i] = item;
  }

  void pop() {
    const T last = items_.back();
    items_.pop_back();
    const std::size_t n = items_.size();
    if (n == 0) return;
    std::size_t i = 0;
    for (;;) {
      const std::size_t first = 4 * i + 1;
      if (first >= n) break;
      std::size_t best = first;
      const std::size_t end = first + 4 < n ? first + 4 : n;
      for (std::size_t c = first + 1; c < end; ++c)
        if (items_[best] > items_[c]) best = c;
      if (!(last > items_[best])) break;
      items_[i] = items_[best];
      i = best;
    }
    items_[i] = last;
  }

 private:
  std::vector<T> items_;
};

}  // namespace cullcheck
