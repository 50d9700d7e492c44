// The occlusion horizon H(α) of thesis ch. 3.1.2 in polar coordinates around the eye.
//
// H maps azimuth α ∈ [0, 2π) to an elevation bound: every direction at azimuth α whose elevation
// lies below H(α), looking past the occluders merged so far, is hidden. Elevations are stored as
// slopes tan β = Δz / horizontal distance (monotone in β, no atan on the hot path).
//
// Representation: the thesis keeps H as a piecewise-constant function in a binary tree whose
// internal nodes hold the min and max of their subtree (Fig. 3.2). Here the pieces are the
// `bins` equal azimuth intervals of width 2π / bins, and the tree is a segment tree over them
// with lazy "raise to at least v" updates, so one update or one query costs O(log bins).
//
// Conservativeness of the discretisation: a shadow raises only bins lying entirely inside its
// azimuth span (inner rounding); a test reads every bin its span touches (outer rounding). Both
// roundings widen by kAngularSlack so that atan2's rounding can never flip a boundary bin.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace cullcheck {

// Added to tested spans and removed from shadow spans, in radians: far above atan2's
// few-ulp error, far below any bin width in use (2π / 2^20 ≈ 6e-6).
inline constexpr double kAngularSlack = 1e-12;

// An azimuth interval [begin, end] with begin ∈ [0, 2π) and begin <= end <= begin + 2π; end may
// exceed 2π when the interval wraps past east.
struct AzimuthSpan {
  double begin = 0.0;
  double end = 0.0;
  bool full_circle() const;
};

class OcclusionHorizon {
 public:
  explicit OcclusionHorizon(std::uint32_t bins = 4096);

  // Lowers every bin to -inf (nothing hidden). Costs the number of nodes written since the
  // last reset.
  void reset();
  // Sets the bins lying entirely outside `span` to +inf: directions outside the view volume's
  // azimuth coverage are hidden from the start (6-DoF mapping of the frustum, ch. 3.1.2).
  void restrict_to(const AzimuthSpan& span);

  // Raises H to at least `slope` over the bins lying entirely inside `span`.
  void raise(const AzimuthSpan& span, double slope);
  // True when an object whose every point over `span` has slope below `max_slope` is hidden:
  // max_slope < min H over every bin touched by `span`.
  bool hides(const AzimuthSpan& span, double max_slope);
  // min H over the bins touched by `span`.
  double min_over(const AzimuthSpan& span);
  // max H over the bins touched by `span`.
  double max_over(const AzimuthSpan& span);

  std::uint32_t bins() const { return bins_; }
  double bin_width() const { return bin_width_; }
  // Current value of one bin (pushes pending raises down; for tests and reports).
  double bin_value(std::uint32_t bin);
  // Every bin's value in order, and the reverse: set every bin and rebuild the tree; both O(bins).
  // (ΔH compares and combines whole horizons bin by bin: the thesis's linked list of pieces.)
  std::vector<double> bin_values();
  void assign(const std::vector<double>& values);
  // Segment-tree nodes visited since construction or the last call to take_node_visits().
  std::uint64_t take_node_visits();
  // Structure invariant: every node's min/max equals the min/max over its children (after
  // applying pending raises). Returns an empty string when it holds, else a description.
  std::string check_invariants() const;

 private:
  void raise_bins(std::uint32_t first, std::uint32_t last, double slope);
  double min_bins(std::uint32_t first, std::uint32_t last);
  void raise_node(std::uint32_t node, std::uint32_t lo, std::uint32_t hi, std::uint32_t first, std::uint32_t last, double slope);
  double min_node(std::uint32_t node, std::uint32_t lo, std::uint32_t hi, std::uint32_t first, std::uint32_t last);
  double max_node(std::uint32_t node, std::uint32_t lo, std::uint32_t hi, std::uint32_t first, std::uint32_t last);
  void apply(std::uint32_t node, double slope);
  void push_down(std::uint32_t node);
  // Calls f(first, last) for the one or two non-wrapping bin ranges of a span.
  template <class F> void for_each_range(const AzimuthSpan& span, bool inner, F&& f) const;

  std::uint32_t bins_;
  double bin_width_;
  void touch(std::uint32_t node) {
    if (dirty_flag_[node]) return;
    dirty_flag_[node] = 1;
    dirty_.push_back(node);
  }

  std::vector<double> min_, max_, pending_;
  // Nodes written since the last reset, so that reset costs what the query touched, not the
  // whole tree (a query touches O(shadows log bins) nodes of 2 * bins).
  std::vector<std::uint32_t> dirty_;
  std::vector<std::uint8_t> dirty_flag_;
  bool all_dirty_ = false;
  std::uint64_t visits_ = 0;
};

}  // namespace cullcheck
