#include "engine/horizon/occlusion_horizon.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "core/geometry.hpp"

namespace cullcheck {
namespace {
constexpr double kNone = -std::numeric_limits<double>::infinity();
constexpr double kAll = std::numeric_limits<double>::infinity();
}  // namespace

bool AzimuthSpan::full_circle() const { return end - begin >= kTwoPi; }

bool AzimuthSpan::valid() const {
  return std::abs(begin) <= kMaxAzimuth && std::abs(end) <= kMaxAzimuth && begin <= end && slack >= 0.0;
}

OcclusionHorizon::OcclusionHorizon(std::uint32_t bins) : bins_(bins), bin_width_(kTwoPi / bins) {
  if (bins < 2 || (bins & (bins - 1)) != 0 || bins > (1u << 22))
    throw std::invalid_argument("horizon bins must be a power of two in [2, 2^22], got " + std::to_string(bins));
  min_.assign(2 * bins_, kNone);
  max_.assign(2 * bins_, kNone);
  pending_.assign(2 * bins_, kNone);
  dirty_flag_.assign(2 * bins_, 0);
}

void OcclusionHorizon::reset() {
  if (all_dirty_ || dirty_.size() > bins_ / 2) {
    std::fill(min_.begin(), min_.end(), kNone);
    std::fill(max_.begin(), max_.end(), kNone);
    std::fill(pending_.begin(), pending_.end(), kNone);
    std::fill(dirty_flag_.begin(), dirty_flag_.end(), 0);
  } else {
    for (std::uint32_t node : dirty_) {
      min_[node] = max_[node] = pending_[node] = kNone;
      dirty_flag_[node] = 0;
    }
  }
  dirty_.clear();
  all_dirty_ = false;
}

template <class F>
bool OcclusionHorizon::for_each_range(const AzimuthSpan& span, bool inner, F&& f) const {
  if (!span.valid()) return false;
  if (span.full_circle()) {
    f(0u, bins_ - 1);
    return true;
  }
  // Bin indices on the unrolled line [0, 2 * bins): a span may run past 2π once. They are
  // computed in double and converted only once known to be in range: the ends are finite and
  // within ±kMaxAzimuth, but the slack may be huge (or +inf).
  double first, last;
  if (inner) {
    first = std::ceil((span.begin + span.slack) / bin_width_);
    last = std::floor((span.end - span.slack) / bin_width_) - 1;
  } else {
    first = std::floor((span.begin - span.slack) / bin_width_);
    last = std::floor((span.end + span.slack) / bin_width_);
  }
  if (!(first <= last)) return false;
  const double bins = bins_;
  if (last - first + 1 >= bins) {
    f(0u, bins_ - 1);
    return true;
  }
  // Now first and last lie within (kMaxAzimuth + 2π) / bin_width + 1 < 2^28 of zero: exact
  // integers in a double and in an int64.
  const std::int64_t n = bins_;
  std::int64_t lo = static_cast<std::int64_t>(first), hi = static_cast<std::int64_t>(last);
  // Move the range so that it starts in [0, n); it then ends before 2n.
  const std::int64_t shift = (lo >= 0 ? lo / n : (lo - n + 1) / n) * n;
  lo -= shift;
  hi -= shift;
  if (hi < n) {
    f(static_cast<std::uint32_t>(lo), static_cast<std::uint32_t>(hi));
  } else {
    f(static_cast<std::uint32_t>(lo), bins_ - 1);
    f(0u, static_cast<std::uint32_t>(hi - n));
  }
  return true;
}

void OcclusionHorizon::restrict_to(const AzimuthSpan& span) {
  if (!span.valid() || span.full_circle()) return;
  // The complement of the outer-rounded coverage: bins entirely outside the span.
  const double end = std::fmod(span.end, kTwoPi);
  const AzimuthSpan outside{end, end + (kTwoPi - (span.end - span.begin)), span.slack};
  for_each_range(outside, /*inner=*/true, [&](std::uint32_t a, std::uint32_t b) { raise_bins(a, b, kAll); });
}

void OcclusionHorizon::raise(const AzimuthSpan& span, double slope) {
  if (std::isnan(slope)) return;
  for_each_range(span, /*inner=*/true, [&](std::uint32_t a, std::uint32_t b) { raise_bins(a, b, slope); });
}

// An empty or invalid rounding reads no bin and so proves nothing: the loosest bound.
double OcclusionHorizon::min_over(const AzimuthSpan& span) {
  double m = kAll;
  const bool read = for_each_range(span, /*inner=*/false, [&](std::uint32_t a, std::uint32_t b) { m = std::min(m, min_bins(a, b)); });
  return read ? m : kNone;
}

double OcclusionHorizon::max_over(const AzimuthSpan& span) {
  double m = kNone;
  const bool read =
      for_each_range(span, /*inner=*/false, [&](std::uint32_t a, std::uint32_t b) { m = std::max(m, max_node(1, 0, bins_ - 1, a, b)); });
  return read ? m : kAll;
}

bool OcclusionHorizon::hides(const AzimuthSpan& span, double max_slope) {
  return std::isfinite(max_slope) && max_slope < min_over(span);
}

double OcclusionHorizon::bin_value(std::uint32_t bin) { return min_bins(bin, bin); }

std::vector<double> OcclusionHorizon::bin_values() {
  for (std::uint32_t node = 1; node < bins_; ++node) push_down(node);
  visits_ += bins_;
  return {min_.begin() + bins_, min_.end()};
}

void OcclusionHorizon::assign(const std::vector<double>& values) {
  if (values.size() != bins_) throw std::invalid_argument("assign: expected " + std::to_string(bins_) + " bin values");
  // A NaN bin would drop out of every min and max (comparisons with NaN are false); as −inf it
  // hides nothing.
  std::transform(values.begin(), values.end(), min_.begin() + bins_, [](double v) { return std::isnan(v) ? kNone : v; });
  std::copy(min_.begin() + bins_, min_.end(), max_.begin() + bins_);
  std::fill(pending_.begin(), pending_.end(), kNone);
  all_dirty_ = true;
  for (std::uint32_t node = bins_ - 1; node >= 1; --node) {
    min_[node] = std::min(min_[2 * node], min_[2 * node + 1]);
    max_[node] = std::max(max_[2 * node], max_[2 * node + 1]);
  }
  visits_ += bins_;
}

std::uint64_t OcclusionHorizon::take_node_visits() {
  const std::uint64_t v = visits_;
  visits_ = 0;
  return v;
}

void OcclusionHorizon::apply(std::uint32_t node, double slope) {
  touch(node);
  min_[node] = std::max(min_[node], slope);
  max_[node] = std::max(max_[node], slope);
  pending_[node] = std::max(pending_[node], slope);
}

void OcclusionHorizon::push_down(std::uint32_t node) {
  if (pending_[node] == kNone) return;
  apply(2 * node, pending_[node]);
  apply(2 * node + 1, pending_[node]);
  pending_[node] = kNone;
}

void OcclusionHorizon::raise_bins(std::uint32_t first, std::uint32_t last, double slope) {
  raise_node(1, 0, bins_ - 1, first, last, slope);
}

double OcclusionHorizon::min_bins(std::uint32_t first, std::uint32_t last) { return min_node(1, 0, bins_ - 1, first, last); }

void OcclusionHorizon::raise_node(std::uint32_t node, std::uint32_t lo, std::uint32_t hi, std::uint32_t first,
                                  std::uint32_t last, double slope) {
  ++visits_;
  if (slope <= min_[node]) return;  // already at least this high everywhere below
  if (first <= lo && hi <= last) {
    apply(node, slope);
    return;
  }
  push_down(node);
  const std::uint32_t mid = lo + (hi - lo) / 2;
  if (first <= mid) raise_node(2 * node, lo, mid, first, last, slope);
  if (last > mid) raise_node(2 * node + 1, mid + 1, hi, first, last, slope);
  touch(node);
  min_[node] = std::min(min_[2 * node], min_[2 * node + 1]);
  max_[node] = std::max(max_[2 * node], max_[2 * node + 1]);
}

double OcclusionHorizon::min_node(std::uint32_t node, std::uint32_t lo, std::uint32_t hi, std::uint32_t first,
                                  std::uint32_t last) {
  ++visits_;
  if (first <= lo && hi <= last) return min_[node];
  push_down(node);
  const std::uint32_t mid = lo + (hi - lo) / 2;
  double m = kAll;
  if (first <= mid) m = std::min(m, min_node(2 * node, lo, mid, first, last));
  if (last > mid) m = std::min(m, min_node(2 * node + 1, mid + 1, hi, first, last));
  return m;
}

double OcclusionHorizon::max_node(std::uint32_t node, std::uint32_t lo, std::uint32_t hi, std::uint32_t first,
                                  std::uint32_t last) {
  ++visits_;
  if (first <= lo && hi <= last) return max_[node];
  push_down(node);
  const std::uint32_t mid = lo + (hi - lo) / 2;
  double m = kNone;
  if (first <= mid) m = std::max(m, max_node(2 * node, lo, mid, first, last));
  if (last > mid) m = std::max(m, max_node(2 * node + 1, mid + 1, hi, first, last));
  return m;
}

std::string OcclusionHorizon::check_invariants() const {
  for (std::uint32_t node = 1; node < bins_; ++node) {
    const std::uint32_t l = 2 * node, r = l + 1;
    const double lmin = std::max(min_[l], pending_[node]), rmin = std::max(min_[r], pending_[node]);
    const double lmax = std::max(max_[l], pending_[node]), rmax = std::max(max_[r], pending_[node]);
    if (min_[node] != std::min(lmin, rmin))
      return "node " + std::to_string(node) + ": min " + std::to_string(min_[node]) + " differs from its children's";
    if (max_[node] != std::max(lmax, rmax))
      return "node " + std::to_string(node) + ": max " + std::to_string(max_[node]) + " differs from its children's";
    if (min_[node] > max_[node]) return "node " + std::to_string(node) + ": min above max";
  }
  return {};
}

}  // namespace cullcheck
