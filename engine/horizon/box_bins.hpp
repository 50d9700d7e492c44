// The horizon bins an axis-aligned box's azimuth span touches, and those a shadow raises, found
// without the span (issue 17: box_span's two atan2 were a quarter of a VbAoI graph, where every
// quadtree cell and building box is tested from some 280,000 eyes).
//
// box_hidden tests a box by the bins OcclusionHorizon::hides reads for box_span(box, eye): the
// outer rounding floor((begin - slack) / w) .. floor((end + slack) / w) of its span. Those two
// integers are what matters, not the span's bits. Here they come from the box's two tangent
// corners, picked by where the eye lies (one of eight regions around the box), and each corner
// direction's bin, found by one division and cross products with the bin boundaries' unit
// vectors. Each boundary test also bounds how far (in radians) the direction lies from the
// boundary; the answer is given only when both ends lie farther from their boundaries than
// everything box_span's ends may differ by (their slack, at most `slack_bound`, plus 1e-11 rad,
// thousands of times atan2's and the subtractions' rounding). Otherwise, and for an eye inside,
// on or within 1e-6 of the box's size of it (where box_span may find no span), none is given and
// the caller computes the span. So the bins are box_span's whenever they are given
// (properties/box_bins_test.cpp, in horizon_structure_test, holds this on drawn boxes, eyes on
// the boxes' edge lines and corners within 1e-15 to 1e-6 rad of a bin boundary).
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "core/geometry.hpp"

namespace cullcheck {

// Unit vectors of the bin boundaries in the first octant, m · w for m = 0 .. bins / 8 (w = 2π /
// bins): every octant's boundaries are these reflected, as bins / 8 is whole. Empty below 8 bins.
class OctantBoundaries {
 public:
  explicit OctantBoundaries(std::uint32_t bins);
  std::uint32_t bins() const { return bins_; }
  double width() const { return width_; }                // 2π / bins, as OcclusionHorizon's
  double bins_per_radian() const { return per_radian_; }  // 1 / width, for first guesses only
  const std::vector<Vec2>& unit() const { return unit_; }

 private:
  std::uint32_t bins_;
  double width_, per_radian_;
  std::vector<Vec2> unit_;
};

// OcclusionHorizon's outer rounding of a span: first in [0, bins), last < first + bins (past
// bins when the span wraps past east).
struct BinRange {
  std::int64_t first = 0, last = 0;
};

// The outer rounding of box_span(box, eye)'s span on `boundaries`' bins, when it is certain
// (see above); nullopt otherwise.
std::optional<BinRange> box_outer_bins(const Box2& box, Vec2 eye, const OctantBoundaries& boundaries);

// A shadow's bins the same way (the guarded ΔH's certainly visible buildings, whose tangent
// vertices are fixed for its region): the inner rounding ceil((begin + slack) / w) ..
// floor((end - slack) / w) - 1 that OcclusionHorizon::raise takes of the span span_between
// gives for the tangent directions `dlo` and `dhi` (tangent vertex - eye) and its `slack`. Given
// only when the span is certain to exist and lie below a quarter turn (cross and dot products of
// the directions positive) and both ends clear their bins' boundaries by the slack plus 1e-11
// rad; an empty rounding (first > last) is an answer too: nothing is raised.
std::optional<BinRange> span_inner_bins(Vec2 dlo, Vec2 dhi, double slack, const OctantBoundaries& boundaries);

}  // namespace cullcheck
