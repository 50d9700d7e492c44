// Set arithmetic on ascending vectors (PVSs, witnessed sets), written once.
#pragma once

#include <algorithm>
#include <iterator>
#include <vector>

namespace cullcheck {

// The elements of `wanted` that `have` lacks (both ascending): what a PVS misses of a
// witnessed set.
template <class T>
std::vector<T> missing(const std::vector<T>& wanted, const std::vector<T>& have) {
  std::vector<T> out;
  std::set_difference(wanted.begin(), wanted.end(), have.begin(), have.end(), std::back_inserter(out));
  return out;
}

// The elements of either (both ascending).
template <class T>
std::vector<T> united(const std::vector<T>& a, const std::vector<T>& b) {
  std::vector<T> out;
  std::set_union(a.begin(), a.end(), b.begin(), b.end(), std::back_inserter(out));
  return out;
}

// How many elements both hold (both ascending).
template <class T>
std::size_t common_count(const std::vector<T>& a, const std::vector<T>& b) {
  std::size_t n = 0;
  for (auto i = a.begin(), j = b.begin(); i != a.end() && j != b.end();) {
    if (*i < *j) ++i;
    else if (*j < *i) ++j;
    else ++n, ++i, ++j;
  }
  return n;
}

}  // namespace cullcheck
