#include "engine/horizon/occlusion_horizon.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "core/geometry.hpp"

namespace cullcheck {
namespace {
constexpr double kNone = -std::numeric_limits<double>::infinity();
constexpr double kAll = std::numeric_limits<double>::infinity();

// The two folds a horizon query needs, each with its identity, its pick of two values and (with
// SSE2) of two lanes of two. The horizon never holds NaN (raise ignores it, assign turns it into
// −inf), so minpd/maxpd give the exact min and max, whatever the order; only the sign of a zero
// may depend on it, which no comparison sees.
struct MinFold {
  static constexpr double kIdentity = kAll;
  static double pick(double a, double b) { return std::min(a, b); }
#if defined(__SSE2__)
  static __m128d lanes(__m128d a, __m128d b) { return _mm_min_pd(a, b); }
#endif
};
struct MaxFold {
  static constexpr double kIdentity = kNone;
  static double pick(double a, double b) { return std::max(a, b); }
#if defined(__SSE2__)
  static __m128d lanes(__m128d a, __m128d b) { return _mm_max_pd(a, b); }
#endif
};

// Fold over a run of doubles, four at a time in two SSE2 registers.
template <class Fold>
double fold_run(const double* v, std::uint32_t n) {
  std::uint32_t i = 0;
  double m = Fold::kIdentity;
#if defined(__SSE2__)
  __m128d a = _mm_set1_pd(Fold::kIdentity), b = a;
  for (; i + 4 <= n; i += 4) {
    a = Fold::lanes(a, _mm_loadu_pd(v + i));
    b = Fold::lanes(b, _mm_loadu_pd(v + i + 2));
  }
  a = Fold::lanes(a, b);
  m = Fold::pick(_mm_cvtsd_f64(a), _mm_cvtsd_f64(_mm_unpackhi_pd(a, a)));
#endif
  for (; i < n; ++i) m = Fold::pick(m, v[i]);
  return m;
}

void raise_all(double* v, std::uint32_t n, double slope) {
  std::uint32_t i = 0;
#if defined(__SSE2__)
  const __m128d s = _mm_set1_pd(slope);
  for (; i + 2 <= n; i += 2) _mm_storeu_pd(v + i, _mm_max_pd(_mm_loadu_pd(v + i), s));
#endif
  for (; i < n; ++i) v[i] = std::max(v[i], slope);
}

// log2 of the bins per block: about the square root of the bin count, so that a query's two
// partial blocks and its whole blocks cost about the same (4096 bins: 64 blocks of 64).
std::uint32_t block_shift_for(std::uint32_t bins) {
  std::uint32_t log2 = 0;
  while ((1u << log2) < bins) ++log2;
  return (log2 + 1) / 2;
}
}  // namespace

bool AzimuthSpan::full_circle() const { return end - begin >= kTwoPi; }

bool AzimuthSpan::valid() const {
  return std::abs(begin) <= kMaxAzimuth && std::abs(end) <= kMaxAzimuth && begin <= end && slack >= 0.0;
}

OcclusionHorizon::OcclusionHorizon(std::uint32_t bins) : bins_(bins), bin_width_(kTwoPi / bins), octant_(bins) {
  if (bins < 2 || (bins & (bins - 1)) != 0 || bins > (1u << 22))
    throw std::invalid_argument("horizon bins must be a power of two in [2, 2^22], got " + std::to_string(bins));
  block_shift_ = block_shift_for(bins);
  blocks_ = bins_ >> block_shift_;
  bin_.assign(bins_, kNone);
  lift_.assign(blocks_, kNone);
  block_min_.assign(blocks_, kNone);
  block_max_.assign(blocks_, kNone);
  dirty_flag_.assign(blocks_, 0);
}

void OcclusionHorizon::reset() {
  const std::uint32_t size = 1u << block_shift_;
  for (std::uint32_t block : dirty_) {
    if (dirty_flag_[block] == kBinsWritten) std::fill_n(bin_.begin() + (static_cast<std::size_t>(block) << block_shift_), size, kNone);
    lift_[block] = block_min_[block] = block_max_[block] = kNone;
    dirty_flag_[block] = 0;
  }
  dirty_.clear();
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
  return for_each_bin_range(first, last, f);
}

template <class F>
bool OcclusionHorizon::for_each_bin_range(double first, double last, F&& f) const {
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

void OcclusionHorizon::raise_range(const BinRange& range, double slope) {
  if (std::isnan(slope)) return;
  for_each_bin_range(double(range.first), double(range.last), [&](std::uint32_t a, std::uint32_t b) { raise_bins(a, b, slope); });
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
      for_each_range(span, /*inner=*/false, [&](std::uint32_t a, std::uint32_t b) { m = std::max(m, max_bins(a, b)); });
  return read ? m : kAll;
}

// max_slope < min_over(span), answered from the block summaries where they settle it: a block
// whose min lies above max_slope hides it over any part of the block, one whose max does not
// cannot; only the blocks in between are read bin by bin, and the first bin range that fails
// ends the test. The same answer as the full fold, at a fraction of the reads.
bool OcclusionHorizon::hides(const AzimuthSpan& span, double max_slope) {
  if (!std::isfinite(max_slope)) return false;
  bool hidden = true;
  const bool read = for_each_range(span, /*inner=*/false, [&](std::uint32_t first, std::uint32_t last) {
    if (hidden) hidden = hides_bins(first, last, max_slope);
  });
  return read && hidden;
}

bool OcclusionHorizon::hides_range(const BinRange& range, double max_slope) {
  if (!std::isfinite(max_slope)) return false;
  bool hidden = true;
  const bool read = for_each_bin_range(double(range.first), double(range.last), [&](std::uint32_t first, std::uint32_t last) {
    if (hidden) hidden = hides_bins(first, last, max_slope);
  });
  return read && hidden;
}

double OcclusionHorizon::min_over_range(const BinRange& range) {
  double m = kAll;
  const bool read = for_each_bin_range(double(range.first), double(range.last),
                                       [&](std::uint32_t a, std::uint32_t b) { m = std::min(m, min_bins(a, b)); });
  return read ? m : kNone;
}

bool OcclusionHorizon::hides_bins(std::uint32_t first, std::uint32_t last, double max_slope) {
  const std::uint32_t mask = (1u << block_shift_) - 1;
  const std::uint32_t last_block = last >> block_shift_;
  for (std::uint32_t block = first >> block_shift_; block <= last_block; ++block) {
    ++visits_;
    if (max_slope < block_min_[block]) continue;        // every bin of the block lies above
    if (!(max_slope < block_max_[block])) return false;  // no bin of the block does
    const std::uint32_t lo = std::max(first, block << block_shift_), hi = std::min(last, (block << block_shift_) | mask);
    if ((lo & mask) == 0 && (hi & mask) == mask) return false;  // the whole block: its min decides
    visits_ += hi - lo + 1;
    if (!(max_slope < std::max(fold_run<MinFold>(bin_.data() + lo, hi - lo + 1), lift_[block]))) return false;
  }
  return true;
}

double OcclusionHorizon::bin_value(std::uint32_t bin) { return std::max(bin_[bin], lift_[bin >> block_shift_]); }

std::vector<double> OcclusionHorizon::bin_values() {
  std::vector<double> values(bins_);
  for (std::uint32_t i = 0; i < bins_; ++i) values[i] = std::max(bin_[i], lift_[i >> block_shift_]);
  visits_ += bins_;
  return values;
}

void OcclusionHorizon::assign(const std::vector<double>& values) {
  if (values.size() != bins_) throw std::invalid_argument("assign: expected " + std::to_string(bins_) + " bin values");
  // A NaN bin would drop out of every min and max (comparisons with NaN are false); as −inf it
  // hides nothing.
  std::transform(values.begin(), values.end(), bin_.begin(), [](double v) { return std::isnan(v) ? kNone : v; });
  const std::uint32_t size = 1u << block_shift_;
  for (std::uint32_t block = 0; block < blocks_; ++block) {
    const double* v = bin_.data() + (static_cast<std::size_t>(block) << block_shift_);
    lift_[block] = kNone;
    block_min_[block] = fold_run<MinFold>(v, size);
    block_max_[block] = fold_run<MaxFold>(v, size);
    touch(block, kBinsWritten);
  }
  visits_ += bins_;
}

std::uint64_t OcclusionHorizon::take_node_visits() {
  const std::uint64_t v = visits_;
  visits_ = 0;
  return v;
}

void OcclusionHorizon::raise_block(std::uint32_t block, double slope) {
  ++visits_;
  if (slope <= block_min_[block]) return;  // already at least this high everywhere in it
  touch(block, kLifted);
  lift_[block] = std::max(lift_[block], slope);
  block_min_[block] = std::max(block_min_[block], slope);
  block_max_[block] = std::max(block_max_[block], slope);
}

void OcclusionHorizon::raise_part(std::uint32_t block, std::uint32_t first, std::uint32_t last, double slope) {
  ++visits_;
  if (slope <= block_min_[block]) return;
  touch(block, kBinsWritten);
  raise_all(bin_.data() + first, last - first + 1, slope);
  const std::uint32_t size = 1u << block_shift_;
  block_min_[block] = std::max(fold_run<MinFold>(bin_.data() + (static_cast<std::size_t>(block) << block_shift_), size), lift_[block]);
  block_max_[block] = std::max(block_max_[block], slope);
  visits_ += (last - first + 1) + size;
}

void OcclusionHorizon::raise_bins(std::uint32_t first, std::uint32_t last, double slope) {
  const std::uint32_t mask = (1u << block_shift_) - 1;
  std::uint32_t block = first >> block_shift_;
  const std::uint32_t last_block = last >> block_shift_;
  for (; block <= last_block; ++block) {
    const std::uint32_t lo = std::max(first, block << block_shift_), hi = std::min(last, (block << block_shift_) | mask);
    if (lo == block << block_shift_ && hi == ((block << block_shift_) | mask))
      raise_block(block, slope);
    else
      raise_part(block, lo, hi, slope);
  }
}

namespace {
// The min (or max) over bins [first, last] of a flat horizon. A bin's value is max(own, lift), so
// over part of a block the fold is max(fold of own values, lift) for either; whole blocks read
// their summary `block_value`.
template <class Fold>
double fold_bins(const double* bins, const double* lift, const double* block_value, std::uint32_t shift, std::uint32_t first,
                 std::uint32_t last, std::uint64_t& visits) {
  const std::uint32_t mask = (1u << shift) - 1;
  const std::uint32_t first_block = first >> shift, last_block = last >> shift;
  auto block_part = [&](std::uint32_t block, std::uint32_t lo, std::uint32_t hi) {
    if ((lo & mask) == 0 && (hi & mask) == mask) return ++visits, block_value[block];
    visits += hi - lo + 1;
    return std::max(fold_run<Fold>(bins + lo, hi - lo + 1), lift[block]);
  };
  if (first_block == last_block) return block_part(first_block, first, last);
  const double ends = Fold::pick(block_part(first_block, first, first | mask), block_part(last_block, last & ~mask, last));
  const std::uint32_t inner = last_block - first_block - 1;
  visits += inner;
  return Fold::pick(ends, fold_run<Fold>(block_value + first_block + 1, inner));
}
}  // namespace

double OcclusionHorizon::min_bins(std::uint32_t first, std::uint32_t last) {
  return fold_bins<MinFold>(bin_.data(), lift_.data(), block_min_.data(), block_shift_, first, last, visits_);
}

double OcclusionHorizon::max_bins(std::uint32_t first, std::uint32_t last) {
  return fold_bins<MaxFold>(bin_.data(), lift_.data(), block_max_.data(), block_shift_, first, last, visits_);
}

std::string OcclusionHorizon::check_invariants() const {
  const std::uint32_t size = 1u << block_shift_;
  for (std::uint32_t block = 0; block < blocks_; ++block) {
    const double* v = bin_.data() + (static_cast<std::size_t>(block) << block_shift_);
    double lo = kAll, hi = kNone;
    for (std::uint32_t i = 0; i < size; ++i) {
      lo = std::min(lo, std::max(v[i], lift_[block]));
      hi = std::max(hi, std::max(v[i], lift_[block]));
    }
    if (block_min_[block] != lo)
      return "block " + std::to_string(block) + ": min " + std::to_string(block_min_[block]) + " differs from its bins'";
    if (block_max_[block] != hi)
      return "block " + std::to_string(block) + ": max " + std::to_string(block_max_[block]) + " differs from its bins'";
    if (block_max_[block] != kNone && !dirty_flag_[block]) return "block " + std::to_string(block) + ": raised but not marked for reset";
    if (dirty_flag_[block] != kBinsWritten)
      for (std::uint32_t i = 0; i < size; ++i)
        if (v[i] != kNone) return "block " + std::to_string(block) + ": a bin written but the block not marked for refilling";
  }
  return {};
}

}  // namespace cullcheck
