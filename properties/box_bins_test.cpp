// box_outer_bins and span_inner_bins (engine/horizon/box_bins.hpp) against the spans they stand
// in for. box_outer_bins: whenever it
// gives a bin range, that range is the outer rounding OcclusionHorizon::hides reads for
// box_span(box, eye), floor((begin - slack) / w) .. floor((end + slack) / w), and hides_range
// answers as hides does. Drawn boxes at plan coordinates up to 1e7, eyes anywhere around them,
// eyes on a box's edge lines (two corners in one direction), and boxes with a corner placed within
// 1e-15 to 1e-6 rad of a bin boundary as the eye sees it, on 8 to 2^20 bins. span_inner_bins:
// whenever it gives a bin range, that range is the inner rounding OcclusionHorizon::raise takes
// of convex_span's span, ceil((begin + slack) / w) .. floor((end - slack) / w) - 1, and
// raise_range raises the horizon as raise does; over boxes drawn as above and convex polygons.
#include <gtest/gtest.h>
#include <rapidcheck.h>

#include <cmath>
#include <iostream>
#include <optional>
#include <vector>

#include "engine/horizon/box_bins.hpp"
#include "engine/horizon/occlusion_horizon.hpp"
#include "engine/horizon/polar_geometry.hpp"
#include "properties/property_run.hpp"

namespace cullcheck {
namespace {

// OcclusionHorizon::for_each_range's outer rounding, restated.
BinRange outer_rounding(const AzimuthSpan& s, std::uint32_t bins) {
  const double w = kTwoPi / bins;
  return {std::int64_t(std::floor((s.begin - s.slack) / w)), std::int64_t(std::floor((s.end + s.slack) / w))};
}

// How far (radians) the nearer end of a span lies from a bin boundary.
double nearest_boundary(const AzimuthSpan& s, std::uint32_t bins) {
  const double w = kTwoPi / bins;
  auto off = [&](double a) {
    const double x = a / w;
    return std::abs(x - std::round(x)) * w;
  };
  return std::min(off(s.begin), off(s.end));
}

// One case's draws both properties share: a bin count, a coordinate offset and a uniform
// number in [0, 1] per call.
struct Draw {
  std::uint32_t bins = *rc::gen::element(8u, 64u, 1024u, 4096u, 16384u, 1u << 20);
  double w = kTwoPi / bins;
  double offset = *rc::gen::element(0.0, 1e3, -2.5e5, 1e6, 1e7);
  static double unit() { return *rc::gen::inRange(0, 1000000) / 1e6; }
};

// The low corner of a width x height box one of whose corners the eye sees within a hair (1e-15
// to 1e-6 rad, or none) of a bin boundary.
Vec2 box_with_a_corner_at_a_boundary(const Draw& d, Vec2 eye, double width, double height) {
  const double k = std::floor(d.unit() * d.bins);
  const double hair = *rc::gen::element(0.0, 1e-15, -1e-15, 1e-13, -1e-13, 2e-12, -2e-12, 5e-12, -5e-12, 1e-11, -1e-11, 1e-9, -1e-9, 1e-6, -1e-6);
  const double angle = k * d.w + hair, r = 1.0 + 300.0 * d.unit();
  const Vec2 corner{eye.x + r * std::cos(angle), eye.y + r * std::sin(angle)};
  // The corner is the box's low, right, high or left corner.
  const int which = *rc::gen::inRange(0, 4);
  return {corner.x - (which == 1 || which == 2 ? width : 0.0), corner.y - (which >= 2 ? height : 0.0)};
}

TEST(BoxBins, GivenOnlyWhereTheyAreTheSpansOuterRounding) {
  int taken = 0, declined = 0, no_span = 0, near_boundary = 0, near_taken = 0, on_edge_line = 0, on_edge_taken = 0, far_out = 0;
  const PropertyOutcome run = run_property("box_outer_bins equals the span's outer rounding", 3000, true, [&] {
    const Draw draw;
    const std::uint32_t bins = draw.bins;
    const double w = draw.w, offset = draw.offset;
    auto unit = &Draw::unit;
    const double width = 1e-3 + 200.0 * unit(), height = 1e-3 + 200.0 * unit();
    const int mode = *rc::gen::inRange(0, 3);
    Vec2 eye{offset + 400.0 * (unit() - 0.5), offset + 400.0 * (unit() - 0.5)};
    Box2 box;
    if (mode == 0) {  // anywhere
      box.lo = {offset + 300.0 * (unit() - 0.5), offset + 300.0 * (unit() - 0.5)};
    } else if (mode == 1) {  // the eye on the line of one of the box's edges
      box.lo = {offset + 300.0 * (unit() - 0.5), offset + 300.0 * (unit() - 0.5)};
      const int edge = *rc::gen::inRange(0, 4);
      if (edge == 0) eye.y = box.lo.y;
      if (edge == 1) eye.y = box.lo.y + height;
      if (edge == 2) eye.x = box.lo.x;
      if (edge == 3) eye.x = box.lo.x + width;
    } else {  // a corner seen within a hair of a bin boundary
      box.lo = box_with_a_corner_at_a_boundary(draw, eye, width, height);
    }
    box.hi = {box.lo.x + width, box.lo.y + height};

    const std::optional<BinRange> fast = box_outer_bins(box, eye, OctantBoundaries(bins));
    const std::optional<ConvexSpan> exact = box_span(box, eye);
    if (!exact) {
      RC_ASSERT(!fast);
      ++no_span;
      return;
    }
    const bool near = nearest_boundary(exact->span, bins) < 1e-8;
    const bool edge_line = eye.x == box.lo.x || eye.x == box.hi.x || eye.y == box.lo.y || eye.y == box.hi.y;
    near_boundary += near ? 1 : 0;
    on_edge_line += edge_line ? 1 : 0;
    if (!fast) {
      ++declined;
      return;
    }
    ++taken;
    near_taken += near ? 1 : 0;
    on_edge_taken += edge_line ? 1 : 0;
    far_out += std::abs(eye.x) > 5e6 ? 1 : 0;
    const BinRange want = outer_rounding(exact->span, bins);
    RC_ASSERT(fast->first == want.first);
    RC_ASSERT(fast->last == want.last);
    // And the horizon answers alike, over a horizon raised somewhere around the span (up to
    // 16,384 bins: a finer horizon costs megabytes a case).
    if (bins > 16384u) return;
    OcclusionHorizon horizon(bins);
    const int raises = *rc::gen::inRange(0, 6);
    for (int i = 0; i < raises; ++i) {
      const double begin = exact->span.begin + (unit() - 0.5) * 4.0 * (exact->span.end - exact->span.begin + w);
      horizon.raise({begin, begin + unit() * 3.0, kAngularSlack}, unit());
    }
    const double slope = unit();
    RC_ASSERT(horizon.hides_range(*fast, slope) == horizon.hides(exact->span, slope));
  });
  ASSERT_TRUE(run.held);
  if (reproducing()) return;
  std::cerr << "cases " << run.cases << ": bins given " << taken << ", declined " << declined << ", no span " << no_span
            << "; ends within 1e-8 rad of a boundary " << near_boundary << " (given " << near_taken << "); eye on an edge line "
            << on_edge_line << " (given " << on_edge_taken << "); given at coordinates near 1e7 " << far_out << "\n";
  // The hard cases were reached: most boxes are answered, ends near a boundary are met (and some
  // of those, farther than the margin, still answered). An eye on an edge line sees two corners
  // in one direction, an axis, which is a bin boundary: those are met and never answered.
  EXPECT_GE(taken, run.cases / 2);
  EXPECT_GE(near_boundary, run.cases / 20);
  EXPECT_GE(near_taken, 1);
  EXPECT_GE(on_edge_line, run.cases / 20);
  EXPECT_EQ(on_edge_taken, 0);
  EXPECT_GE(far_out, run.cases / 20);
  EXPECT_GE(no_span, 1);
}

// OcclusionHorizon::for_each_range's inner rounding, restated.
BinRange inner_rounding(const AzimuthSpan& s, std::uint32_t bins) {
  const double w = kTwoPi / bins;
  return {std::int64_t(std::ceil((s.begin + s.slack) / w)), std::int64_t(std::floor((s.end - s.slack) / w)) - 1};
}

TEST(ShadowBins, GivenOnlyWhereTheyAreTheSpansInnerRounding) {
  int taken = 0, empty_taken = 0, declined = 0, wide = 0, near_boundary = 0, near_taken = 0, far_out = 0, polygons = 0;
  const PropertyOutcome run = run_property("span_inner_bins equals the span's inner rounding", 3000, true, [&] {
    const Draw draw;
    const std::uint32_t bins = draw.bins;
    const double w = draw.w, offset = draw.offset;
    auto unit = &Draw::unit;
    const Vec2 eye{offset + 400.0 * (unit() - 0.5), offset + 400.0 * (unit() - 0.5)};
    std::vector<Vec2> ring;
    const int mode = *rc::gen::inRange(0, 4);  // half the cases aim a corner at a boundary
    if (mode == 0) {  // a convex polygon: n points on a circle, counter-clockwise
      ++polygons;
      const int n = *rc::gen::inRange(3, 17);
      const Vec2 centre{offset + 600.0 * (unit() - 0.5), offset + 600.0 * (unit() - 0.5)};
      const double r = 1e-3 + 100.0 * unit(), turn = kTwoPi * unit();
      for (int i = 0; i < n; ++i) {
        const double a = turn + kTwoPi * (i + 0.8 * unit()) / n;
        ring.push_back({centre.x + r * std::cos(a), centre.y + r * std::sin(a)});
      }
    } else {  // a box, with (modes 2 and 3) a corner seen within a hair of a bin boundary
      const double width = 1e-3 + 200.0 * unit(), height = 1e-3 + 200.0 * unit();
      Vec2 lo{offset + 300.0 * (unit() - 0.5), offset + 300.0 * (unit() - 0.5)};
      if (mode >= 2) lo = box_with_a_corner_at_a_boundary(draw, eye, width, height);
      const auto corners = box_corners(Box2{lo, {lo.x + width, lo.y + height}});
      ring.assign(corners.begin(), corners.end());
    }
    const std::optional<ConvexSpan> exact = convex_span(ring, eye);
    if (!exact) return;
    const Vec2 lo = ring[exact->first_tangent], hi = ring[exact->last_tangent];
    const Vec2 dlo = lo - eye, dhi = hi - eye;
    const double llo = length(dlo), lhi = length(dhi);
    RC_ASSERT(llo == exact->first_distance);
    RC_ASSERT(lhi == exact->last_distance);
    const double slack = tangent_slack(lo, hi, eye, llo, lhi);
    RC_ASSERT(slack == exact->span.slack);
    const std::optional<BinRange> fast = span_inner_bins(dlo, dhi, slack, OctantBoundaries(bins));
    const bool near = nearest_boundary(exact->span, bins) < 1e-8;
    near_boundary += near ? 1 : 0;
    if (!fast) {
      ++declined;
      wide += exact->span.end - exact->span.begin > kPi / 2 - 1e-9 ? 1 : 0;
      return;
    }
    ++taken;
    near_taken += near ? 1 : 0;
    far_out += std::abs(eye.x) > 5e6 ? 1 : 0;
    const BinRange want = inner_rounding(exact->span, bins);
    RC_ASSERT(fast->first == want.first);
    RC_ASSERT(fast->last == want.last);
    empty_taken += fast->first > fast->last ? 1 : 0;
    // The horizon raised either way holds the same bins.
    if (bins > 16384u) return;
    OcclusionHorizon by_span(bins), by_bins(bins);
    const double slope = unit();
    by_span.raise(exact->span, slope);
    by_bins.raise_range(*fast, slope);
    for (std::int64_t b = want.first - 2; b <= want.last + 2; ++b) {
      const AzimuthSpan bin{(double(b) + 0.25) * w, (double(b) + 0.75) * w, 0.0};
      if (!bin.valid()) continue;
      RC_ASSERT(by_span.min_over(bin) == by_bins.min_over(bin));
    }
  });
  ASSERT_TRUE(run.held);
  if (reproducing()) return;
  std::cerr << "cases " << run.cases << ": bins given " << taken << " (empty " << empty_taken << "), declined " << declined
            << " (spans of a quarter turn or more " << wide << "); ends within 1e-8 rad of a boundary " << near_boundary
            << " (given " << near_taken << "); given at coordinates near 1e7 " << far_out << "; polygons " << polygons << "\n";
  EXPECT_GE(taken, run.cases / 2);
  EXPECT_GE(empty_taken, 1);
  EXPECT_GE(wide, 1);
  EXPECT_GE(near_boundary, run.cases / 20);
  EXPECT_GE(near_taken, 1);
  EXPECT_GE(far_out, run.cases / 20);
}

}  // namespace
}  // namespace cullcheck
