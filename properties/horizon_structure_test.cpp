// Structure invariants of the occlusion horizon and the quadtree (design: "Structure
// invariants"): the flat horizon agrees with a plain array of bins under random raises, queries
// and resets, including spans that wrap at 0 / 2π, and its block min/max invariant holds throughout.
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "core/geometry.hpp"
#include "core/scene_io.hpp"
#include "engine/horizon/fast_angle.hpp"
#include "engine/horizon/occlusion_horizon.hpp"
#include "engine/horizon/polar_geometry.hpp"
#include "engine/horizon/quad_heap.hpp"
#include "engine/horizon/object_space_horizon.hpp"
#include "engine/spatial/quadtree.hpp"
#include "generators/rapidcheck_gens.hpp"

namespace cullcheck {
namespace {

// The plain model: one value per bin; a raise covers bins wholly inside the span, a query
// reads every bin the span touches.
struct BinModel {
  std::uint32_t bins;
  std::vector<double> value;
  explicit BinModel(std::uint32_t n) : bins(n), value(n, -std::numeric_limits<double>::infinity()) {}
  double width() const { return kTwoPi / bins; }
  bool inside(std::uint32_t b, const AzimuthSpan& s) const {
    if (s.full_circle()) return true;
    for (double shift : {0.0, kTwoPi}) {
      const double lo = b * width() + shift, hi = (b + 1) * width() + shift;
      if (lo >= s.begin + kAngularSlack && hi <= s.end - kAngularSlack) return true;
    }
    return false;
  }
  bool touches(std::uint32_t b, const AzimuthSpan& s) const {
    if (s.full_circle()) return true;
    for (double shift : {-kTwoPi, 0.0, kTwoPi}) {
      const double lo = b * width() + shift, hi = (b + 1) * width() + shift;
      if (hi >= s.begin - kAngularSlack && lo <= s.end + kAngularSlack) return true;
    }
    return false;
  }
};

AzimuthSpan span_from(double begin_fraction, double length_fraction) {
  const double begin = begin_fraction * kTwoPi;
  return {begin, begin + length_fraction * kTwoPi};
}

RC_GTEST_PROP(OcclusionHorizon, AgreesWithPlainBinsAndKeepsInvariants, ()) {
  const std::uint32_t bins = 1u << *rc::gen::inRange(1, 10);
  OcclusionHorizon horizon(bins);
  BinModel model(bins);
  const int steps = *rc::gen::inRange(1, 60);
  for (int step = 0; step < steps; ++step) {
    const double begin = *rc::gen::inRange(0, 1000) / 1000.0;
    const double length = *rc::gen::inRange(0, 1001) / 1000.0;
    const AzimuthSpan span = span_from(begin, length);
    if (*rc::gen::arbitrary<bool>()) {
      const double slope = *rc::gen::inRange(-100, 100) / 10.0;
      horizon.raise(span, slope);
      for (std::uint32_t b = 0; b < bins; ++b)
        if (model.inside(b, span)) model.value[b] = std::max(model.value[b], slope);
    } else if (*rc::gen::inRange(0, 20) == 0) {
      horizon.reset();
      std::fill(model.value.begin(), model.value.end(), -std::numeric_limits<double>::infinity());
    } else {
      double lowest = std::numeric_limits<double>::infinity(), highest = -lowest;
      for (std::uint32_t b = 0; b < bins; ++b)
        if (model.touches(b, span)) lowest = std::min(lowest, model.value[b]), highest = std::max(highest, model.value[b]);
      RC_ASSERT(horizon.min_over(span) == lowest);
      RC_ASSERT(horizon.max_over(span) == highest);
      // hides() answers from block summaries where it can: the same answer as the full fold, at
      // the lowest bin itself, just below it, at the highest and at a random slope.
      const double random_slope = *rc::gen::inRange(-110, 110) / 10.0;
      for (double slope : {lowest, std::nextafter(lowest, -HUGE_VAL), highest, random_slope})
        RC_ASSERT(horizon.hides(span, slope) == (std::isfinite(slope) && slope < lowest));
    }
    RC_ASSERT(horizon.check_invariants() == "");
  }
  for (std::uint32_t b = 0; b < bins; ++b) RC_ASSERT(horizon.bin_value(b) == model.value[b]);
  RC_ASSERT(horizon.bin_values() == model.value);
  // assign() then reset(): the blocks follow the assigned bins, and reset lowers all of them.
  horizon.assign(model.value);
  RC_ASSERT(horizon.check_invariants() == "");
  RC_ASSERT(horizon.bin_values() == model.value);
  horizon.reset();
  RC_ASSERT(horizon.check_invariants() == "");
  RC_ASSERT(horizon.max_over({0.0, kTwoPi}) == -std::numeric_limits<double>::infinity());
}

// The sweeps' four-way heap pops in sorted order, whatever the pushes and pops between: items
// with many equal distances, told apart by index as SweepItem does, against a sort of the same.
RC_GTEST_PROP(QuadHeap, PopsInTheOrderOfASort, ()) {
  struct Item {
    int distance;
    int index;
    bool operator>(const Item& o) const { return distance != o.distance ? distance > o.distance : index > o.index; }
    bool operator==(const Item& o) const { return distance == o.distance && index == o.index; }
  };
  QuadHeap<Item> heap;
  std::vector<Item> model;  // what the heap holds
  const int steps = *rc::gen::inRange(1, 400);
  for (int step = 0, next = 0; step < steps; ++step) {
    if (model.empty() || *rc::gen::inRange(0, 3) != 0) {
      const Item item{*rc::gen::inRange(0, 20), next++};
      heap.push(item);
      model.push_back(item);
    } else {
      const auto least = std::min_element(model.begin(), model.end(), [](const Item& a, const Item& b) { return b > a; });
      RC_ASSERT(heap.top() == *least);
      heap.pop();
      model.erase(least);
    }
    RC_ASSERT(heap.size() == model.size());
  }
  std::sort(model.begin(), model.end(), [](const Item& a, const Item& b) { return b > a; });
  for (const Item& item : model) {
    RC_ASSERT(heap.top() == item);
    heap.pop();
  }
  RC_ASSERT(heap.empty());
}

// fast_atan2 (the spans' angles) stays within 2e-15 rad of libm's atan2, a thousandth of the
// slack every span carries, over directions of every octant and magnitude, near the table's
// breakpoints and the octants' diagonals; it keeps atan2's exact values on the axes and its
// conventions for zeros, infinities and NaN.
RC_GTEST_PROP(FastAngle, Atan2WithinTwoFemtoradiansOfLibm, ()) {
  const double t = *rc::gen::inRange(0, 1 << 20) / double(1 << 20);
  // Near a sixteenth or the diagonal half the time: where the reduction changes branch.
  const int k = *rc::gen::inRange(0, 17);
  const double near = k / 16.0 + *rc::gen::inRange(-1000, 1001) * 1e-16;
  const double ratio = *rc::gen::arbitrary<bool>() ? t : std::clamp(near, 0.0, 1.0);
  const double scale = std::ldexp(1.0, *rc::gen::inRange(-60, 60));
  const bool steep = *rc::gen::arbitrary<bool>();
  double x = scale, y = ratio * scale;
  if (steep) std::swap(x, y);
  if (*rc::gen::arbitrary<bool>()) x = -x;
  if (*rc::gen::arbitrary<bool>()) y = -y;
  const double fast = fast_atan2(y, x), libm = std::atan2(y, x);
  RC_ASSERT(std::abs(fast - libm) <= 2e-15);
  const double azimuth = fast_azimuth({x, y});
  RC_ASSERT(azimuth >= 0.0);
  RC_ASSERT(azimuth < kTwoPi);
}

TEST(FastAngle, ExactOnAxesAndLibmAtTheEdges) {
  const double inf = std::numeric_limits<double>::infinity(), nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(fast_atan2(0.0, 1.0), 0.0);
  EXPECT_EQ(fast_atan2(1.0, 0.0), kPi / 2);
  EXPECT_EQ(fast_atan2(0.0, -1.0), kPi);
  EXPECT_EQ(fast_atan2(-0.0, -1.0), -kPi);
  EXPECT_EQ(fast_atan2(-1.0, 0.0), -kPi / 2);
  EXPECT_EQ(fast_atan2(3.0, 3.0), kPi / 4);
  EXPECT_EQ(fast_atan2(0.0, 0.0), std::atan2(0.0, 0.0));
  EXPECT_EQ(fast_atan2(-0.0, -0.0), std::atan2(-0.0, -0.0));
  EXPECT_EQ(fast_atan2(1.0, -inf), std::atan2(1.0, -inf));
  EXPECT_EQ(fast_atan2(inf, inf), std::atan2(inf, inf));
  EXPECT_TRUE(std::isnan(fast_atan2(nan, 1.0)));
  EXPECT_TRUE(std::isnan(fast_atan2(1.0, nan)));
  EXPECT_EQ(fast_azimuth({1.0, -0.0}), 0.0);
  EXPECT_NEAR(fast_azimuth({1.0, -1e-300}), 0.0, 0.0);  // −1e−300 + 2π rounds to 2π: azimuth 0
  // Over a dense sweep of the circle the largest difference from libm, pinned as a bound.
  double worst = 0.0;
  for (int i = 0; i < 100000; ++i) {
    const double a = i * (kTwoPi / 100000) - kPi;
    const double x = 1e3 * std::cos(a), y = 1e3 * std::sin(a);
    worst = std::max(worst, std::abs(fast_atan2(y, x) - std::atan2(y, x)));
  }
  EXPECT_LE(worst, 1e-15);
  EXPECT_GT(worst, 0.0);  // not libm itself: the sweep reaches rounding differences
}

TEST(OcclusionHorizon, WrapAroundEastIsOneInterval) {
  OcclusionHorizon horizon(16);
  // A shadow from 350° to 20° raises the bins on both sides of east and nothing else.
  horizon.raise({350.0 * kPi / 180, 380.0 * kPi / 180}, 1.0);
  // Neither [337.5°, 360°) nor [0, 22.5°) lies wholly inside: both stay low.
  EXPECT_EQ(horizon.bin_value(15), -std::numeric_limits<double>::infinity());
  EXPECT_EQ(horizon.bin_value(0), -std::numeric_limits<double>::infinity());
  horizon.raise({330.0 * kPi / 180, 400.0 * kPi / 180}, 2.0);
  EXPECT_EQ(horizon.bin_value(15), 2.0);
  EXPECT_EQ(horizon.bin_value(0), 2.0);
  EXPECT_EQ(horizon.bin_value(1), -std::numeric_limits<double>::infinity());
  // A test span touching azimuth exactly 0 reads the last bin too.
  EXPECT_EQ(horizon.min_over({0.0, 0.0}), 2.0);
  EXPECT_TRUE(horizon.check_invariants().empty());
}

TEST(OcclusionHorizon, RestrictHidesOnlyBinsOutsideCoverage) {
  OcclusionHorizon horizon(8);
  horizon.restrict_to({kPi / 2, kPi});  // bins 2 and 3 are the coverage
  EXPECT_EQ(horizon.bin_value(2), -std::numeric_limits<double>::infinity());
  EXPECT_EQ(horizon.bin_value(3), -std::numeric_limits<double>::infinity());
  // Bins 1 and 4 touch the coverage at a boundary: slack keeps them open.
  EXPECT_EQ(horizon.bin_value(1), -std::numeric_limits<double>::infinity());
  EXPECT_EQ(horizon.bin_value(4), -std::numeric_limits<double>::infinity());
  EXPECT_EQ(horizon.bin_value(0), std::numeric_limits<double>::infinity());
  EXPECT_EQ(horizon.bin_value(6), std::numeric_limits<double>::infinity());
}

TEST(PolarGeometry, SpanAcrossEastAndTangents) {
  const std::vector<Vec2> square{{10, -1}, {12, -1}, {12, 1}, {10, 1}};
  const auto s = convex_span(square, {0, 0});
  ASSERT_TRUE(s);
  EXPECT_NEAR(s->span.begin, kTwoPi - std::atan2(1.0, 10.0), 1e-12);
  EXPECT_NEAR(s->span.end - s->span.begin, 2 * std::atan2(1.0, 10.0), 1e-12);
  EXPECT_EQ(s->first_tangent, 0u);
  EXPECT_EQ(s->last_tangent, 3u);
  EXPECT_FALSE(convex_span(square, {11, 0}));  // eye inside
  EXPECT_FALSE(convex_span(square, {10, 0}));  // eye on a wall
  // The far chain runs from tangent to tangent behind the front wall; its nearest points are
  // the tangent vertices themselves.
  EXPECT_NEAR(min_far_chain_distance(square, {0, 0}), std::hypot(10.0, 1.0), 1e-12);
  // A wide, shallow slab: the back wall's middle is nearer than either tangent vertex.
  const std::vector<Vec2> slab{{20, -20}, {21, -20}, {21, 20}, {20, 20}};
  EXPECT_NEAR(min_far_chain_distance(slab, {0, 0}), 21.0, 1e-12);
}

// The radar property's counterexample (a mast at a rectangular roof's centroid, which lies on the
// diagonal of its fan triangles): rounding put the eye just outside the triangle, its two
// diagonal vertices in opposite directions, and the span came out as one direction, 0 wide,
// leaving the third vertex out. Every vertex must lie in the span, or there is no span.
TEST(PolarGeometry, AnEyeOnAnEdgeGetsNoSpanOrOneHoldingEveryVertex) {
  const std::vector<Vec2> roof{{-17.293, -20.253}, {-4.652, -20.253}, {-4.652, -5.258}};
  const Vec2 eye{-10.9725, -12.755500000000001};
  const auto s = convex_span(roof, eye);
  if (s) {
    for (const Vec2& v : roof) {
      double a = azimuth_of(v - eye);
      if (a < s->span.begin) a += kTwoPi;
      EXPECT_LE(a, s->span.end + 1e-9) << v.x << ", " << v.y;
    }
  }
  EXPECT_FALSE(s);
}

TEST(Quadtree, InvariantsHoldOnAGrid) {
  Scene scene;
  for (int i = 0; i < 30; ++i)
    for (int j = 0; j < 30; ++j) {
      Building b;
      b.id = static_cast<ObjectId>(i * 30 + j);
      b.height = 5.0 + (i * 7 + j * 3) % 20;
      const double x = i * 20.0, y = j * 20.0;
      b.footprint = {{x, y}, {x + 8 + (j % 3), y}, {x + 8 + (j % 3), y + 10}, {x, y + 10}};
      validate_and_finish(b);
      scene.buildings.push_back(b);
    }
  for (std::uint32_t leaf : {1u, 4u, 8u, 64u}) {
    const Quadtree tree(scene, leaf);
    EXPECT_EQ(tree.check_invariants(scene), "") << "leaf size " << leaf;
    for (const auto& cell : tree.cells())
      if (cell.leaf()) {
        EXPECT_LE(cell.last - cell.first, leaf);
      }
  }
}

// After real culls on generated scenes and cameras, the horizon tree still satisfies its
// invariant, and the quadtree built for any generated scene encloses its buildings.
RC_GTEST_PROP(StructureInvariants, HoldOnGeneratedScenesAfterCulling, ()) {
  const generators::SceneCase c = *generators::rcgen::scene_case();
  const Scene scene = generators::scene_of(c.spec);
  MethodOptions options;
  options.horizon_bins = 256;
  options.quadtree_leaf_size = 4;
  ObjectSpaceHorizonCulling method(scene, ShadowRule::conservative, options);
  RC_ASSERT(method.quadtree().check_invariants(scene) == "");
  (void)method.cull(c.camera);
  RC_ASSERT(method.horizon().check_invariants() == "");
}

}  // namespace
}  // namespace cullcheck
