// The occlusion horizon H(α) of thesis ch. 3.1.2 in polar coordinates around the eye.
//
// H maps azimuth α ∈ [0, 2π) to an elevation bound: every direction at azimuth α whose elevation
// lies below H(α), looking past the occluders merged so far, is hidden. Elevations are stored as
// slopes tan β = Δz / horizontal distance (monotone in β, no atan on the hot path).
//
// Representation: the thesis keeps H as a piecewise-constant function in a binary tree whose
// internal nodes hold the min and max of their subtree (Fig. 3.2). Here the pieces are the
// `bins` equal azimuth intervals of width 2π / bins, stored flat, in blocks of about √bins bins
// (64 for 4096) that keep their min, max and a lazy "raise the whole block to at least v". An
// update or a query reads and writes contiguous doubles: at most two partial blocks bin by bin
// and the whole blocks between them one value each, in SIMD registers two at a time, where the
// segment tree chased O(log bins) nodes through memory with a pending value pushed down on
// every path (issue 17: the tree was a third of ΔH's time).
//
// Conservativeness of the discretisation: a shadow raises only bins lying entirely inside its
// azimuth span (inner rounding); a test reads every bin its span touches (outer rounding). Both
// roundings widen by the span's `slack` (at least kAngularSlack, more for spans computed from
// large coordinates close to the eye: angular_slack) so that rounding can never flip a boundary
// bin.
//
// Failing safe: the horizon may hide a thing only on evidence. A span that is not a valid
// azimuth span (NaN or infinite ends, end before begin, ends beyond ±kMaxAzimuth, NaN slack) or
// whose rounding touches no bin proves nothing: min_over is then −inf (nothing hidden),
// max_over +inf (no bound), raise and restrict_to change nothing. hides() never hides a thing
// whose highest slope is NaN or infinite, and a NaN slope raises nothing. No float is converted
// to an integer before it is known to be a finite bin index in range.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "core/geometry.hpp"
#include "engine/horizon/box_bins.hpp"

namespace cullcheck {

// Added to tested spans and removed from shadow spans, in radians: far above atan2's
// few-ulp error, far below any bin width in use (2π / 2^20 ≈ 6e-6). The least slack of a span.
inline constexpr double kAngularSlack = 1e-12;

// Azimuths farther than this from 0 are not produced by any span construction in the engine
// (their ends lie in [−2π, 4π]); a span reaching beyond is treated as unknown, not reduced.
inline constexpr double kMaxAzimuth = 16.0 * kPi;

// The slack of an azimuth computed from plan coordinates of magnitude up to `magnitude` (the
// larger |x|, |y| of the eye and the point) at plan distance `distance` from the eye. Each
// coordinate is only known to its rounding, about magnitude·ε (ε = 2^−52), and atan2 turns an
// offset across the line of sight into an angle by dividing by the distance: the azimuth is
// off by about magnitude·ε / distance. Four times that, plus kAngularSlack for atan2's own
// error. +inf for a zero distance (such a span reads the whole circle and raises nothing), NaN
// for NaN input (an invalid span).
inline double angular_slack(double magnitude, double distance) {
  return kAngularSlack + 4.0 * std::numeric_limits<double>::epsilon() * magnitude / distance;
}

// An azimuth interval [begin, end] with begin ∈ [0, 2π) and begin <= end <= begin + 2π; end may
// exceed 2π when the interval wraps past east. `slack` bounds the rounding error of both ends.
struct AzimuthSpan {
  double begin = 0.0;
  double end = 0.0;
  double slack = kAngularSlack;
  bool full_circle() const;
  // Finite ends within ±kMaxAzimuth, begin <= end, slack >= 0 (may be +inf).
  bool valid() const;
};

class OcclusionHorizon {
 public:
  explicit OcclusionHorizon(std::uint32_t bins = 4096);

  // Lowers every bin to -inf (nothing hidden). Costs the blocks written since the last reset.
  void reset();
  // Sets the bins lying entirely outside `span` to +inf: directions outside the view volume's
  // azimuth coverage are hidden from the start (6-DoF mapping of the frustum, ch. 3.1.2).
  // An invalid span restricts nothing.
  void restrict_to(const AzimuthSpan& span);

  // Raises H to at least `slope` over the bins lying entirely inside `span`. +inf is a valid
  // slope (hides every direction there: upper bounds of a horizon use it); NaN raises nothing.
  // Callers that compute shadows from geometry pass finite slopes only (a non-finite one comes
  // from degenerate geometry and must not hide anything).
  void raise(const AzimuthSpan& span, double slope);
  // raise() over bins already rounded inward: `range` as span_inner_bins gives it.
  void raise_range(const BinRange& range, double slope);
  // True when an object whose every point over `span` has slope below `max_slope` is hidden:
  // max_slope < min H over every bin touched by `span`. False when max_slope is not finite.
  bool hides(const AzimuthSpan& span, double max_slope);
  // hides() over bins already rounded: `range` as box_outer_bins gives it (the outer rounding of
  // a span, which hides() would compute from the span).
  bool hides_range(const BinRange& range, double max_slope);
  // min_over() over bins already rounded, as hides_range.
  double min_over_range(const BinRange& range);
  // The bin boundaries box_outer_bins reads.
  const OctantBoundaries& octant_boundaries() const { return octant_; }
  // min H over the bins touched by `span`; −inf when the span is invalid or touches no bin.
  double min_over(const AzimuthSpan& span);
  // max H over the bins touched by `span`; +inf when the span is invalid or touches no bin.
  double max_over(const AzimuthSpan& span);

  std::uint32_t bins() const { return bins_; }
  double bin_width() const { return bin_width_; }
  // Current value of one bin (for tests and reports).
  double bin_value(std::uint32_t bin);
  // Every bin's value in order, and the reverse: set every bin and its block; both O(bins).
  // (ΔH compares and combines whole horizons bin by bin: the thesis's linked list of pieces.)
  // assign() takes a NaN value as −inf (nothing hidden there).
  std::vector<double> bin_values();
  void assign(const std::vector<double>& values);
  // Horizon entries (bins and blocks) read or written since construction or the last call to
  // take_node_visits().
  std::uint64_t take_node_visits();
  // Structure invariant: every block's min/max equals the min/max of its bins' values (each the
  // larger of the bin's own and the block's lift). Returns an empty string when it holds, else a
  // description.
  std::string check_invariants() const;

 private:
  void raise_bins(std::uint32_t first, std::uint32_t last, double slope);
  double min_bins(std::uint32_t first, std::uint32_t last);
  // Whether max_slope lies below every bin of [first, last] (hides() over one bin range).
  bool hides_bins(std::uint32_t first, std::uint32_t last, double max_slope);
  double max_bins(std::uint32_t first, std::uint32_t last);
  // Raise or read bins [first, last] of one block, at least one of them and not every one.
  void raise_part(std::uint32_t block, std::uint32_t first, std::uint32_t last, double slope);
  void raise_block(std::uint32_t block, double slope);
  // Marks a block for reset: kLifted when only its summaries and lift were written, kBinsWritten
  // when its bins were too (reset then refills them; a restricted view's dozens of lifted blocks
  // cost four values each instead of a block of bins).
  static constexpr std::uint8_t kLifted = 1, kBinsWritten = 2;
  void touch(std::uint32_t block, std::uint8_t how) {
    if (dirty_flag_[block] == 0) dirty_.push_back(block);
    dirty_flag_[block] = std::max(dirty_flag_[block], how);
  }
  // Calls f(first, last) for the one or two non-wrapping bin ranges of a span; returns whether
  // it called f at all (false for an invalid span or an empty rounding).
  template <class F> bool for_each_range(const AzimuthSpan& span, bool inner, F&& f) const;
  // The same from the unrolled bin indices [first, last] of a rounding (doubles: not yet known
  // to be in range).
  template <class F> bool for_each_bin_range(double first, double last, F&& f) const;

  std::uint32_t bins_;
  double bin_width_;
  std::uint32_t block_shift_;  // a block holds 1 << block_shift_ bins
  std::uint32_t blocks_;
  OctantBoundaries octant_;

  // A bin's value is max(bin_[i], lift_[block]); block_min_/block_max_ hold the min and max of
  // those values over the block.
  std::vector<double> bin_, lift_, block_min_, block_max_;
  // Blocks written since the last reset, so that reset costs what the query touched, not the
  // whole horizon; dirty_flag_ says how (touch).
  std::vector<std::uint32_t> dirty_;
  std::vector<std::uint8_t> dirty_flag_;
  std::uint64_t visits_ = 0;
};

}  // namespace cullcheck
