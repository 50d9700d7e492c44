// Order statistics for per-frame timings and sizes. Medians and p95 use the nearest-rank
// definition on a sorted copy, so they are reproducible and always an observed value.
#pragma once

#include <algorithm>
#include <cmath>
#include <numeric>
#include <vector>

namespace cullcheck {

inline double percentile(std::vector<double> values, double p) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  const double rank = std::ceil(p / 100.0 * static_cast<double>(values.size()));
  const std::size_t index = static_cast<std::size_t>(std::clamp(rank, 1.0, static_cast<double>(values.size()))) - 1;
  return values[index];
}

inline double median(const std::vector<double>& values) { return percentile(values, 50.0); }

inline double mean(const std::vector<double>& values) {
  return values.empty() ? 0.0 : std::accumulate(values.begin(), values.end(), 0.0) / static_cast<double>(values.size());
}

}  // namespace cullcheck
