// The occlusion horizons fail safe (engine/horizon/occlusion_horizon.hpp, engine/image_space/):
// a span or a height the horizon cannot trust — an empty rounding, an inverted range, NaN ends,
// a NaN or infinite slope, ends or coordinates beyond any real scene — never means "culled",
// never raises the horizon, and never reaches a float-to-integer conversion (undefined
// behaviour; the sanitizer build traps it). Each case pins the horizon's literal answer, and
// each method built on a horizon is run on a scene whose geometry overflows.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

#include "core/scene_io.hpp"
#include "engine/horizon/occlusion_horizon.hpp"
#include "engine/horizon/polar_geometry.hpp"
#include "engine/image_space/image_space_horizon.hpp"
#include "engine/method.hpp"
#include "engine/shrinking/circle_tiling.hpp"
#include "engine/shrinking/view_cell.hpp"

namespace cullcheck {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// A 16-bin horizon raised to slope 1 everywhere: anything below slope 1 is hidden wherever a
// span is read, so a "not hidden" answer can only come from the fail-safe rule.
OcclusionHorizon raised_everywhere() {
  OcclusionHorizon h(16);
  h.raise({0.0, kTwoPi}, 1.0);
  return h;
}

std::vector<double> bins_of(OcclusionHorizon& h) { return h.bin_values(); }

// --- OcclusionHorizon (OH(OS), ΔH, the shrinking methods) ------------------------------------

TEST(HorizonFailSafe, ValidSpanBehindARaisedHorizonIsHidden) {
  // The control: the same horizon hides a valid span, a point span included.
  OcclusionHorizon h = raised_everywhere();
  EXPECT_TRUE(h.hides({1.0, 1.5}, 0.5));
  EXPECT_TRUE(h.hides({1.0, 1.0}, 0.5));
  EXPECT_EQ(h.min_over({1.0, 1.5}), 1.0);
  EXPECT_FALSE(h.hides({1.0, 1.5}, 1.0));  // not below: not hidden
}

TEST(HorizonFailSafe, EmptySpanReadsNoBinAndHidesNothing) {
  // Its rounding touches no bin: ends a hair apart the wrong way (within a bin), and a span
  // whose raise rounds to nothing.
  OcclusionHorizon h = raised_everywhere();
  const AzimuthSpan empty{1.0, std::nextafter(1.0, 0.0), 0.0};
  EXPECT_FALSE(empty.valid());
  EXPECT_EQ(h.min_over(empty), -kInf);
  EXPECT_EQ(h.max_over(empty), kInf);
  EXPECT_FALSE(h.hides(empty, 0.5));
  // A raise narrower than a bin raises no bin.
  OcclusionHorizon low(16);
  low.raise({0.1, 0.2}, 3.0);
  EXPECT_EQ(bins_of(low), std::vector<double>(16, -kInf));
}

TEST(HorizonFailSafe, InvertedSpanHidesNothingAndRaisesNothing) {
  OcclusionHorizon h = raised_everywhere();
  const AzimuthSpan inverted{3.0, 1.0};
  EXPECT_FALSE(inverted.valid());
  EXPECT_EQ(h.min_over(inverted), -kInf);
  EXPECT_EQ(h.max_over(inverted), kInf);
  EXPECT_FALSE(h.hides(inverted, 0.5));
  OcclusionHorizon low(16);
  low.raise(inverted, 3.0);
  low.restrict_to(inverted);
  EXPECT_EQ(bins_of(low), std::vector<double>(16, -kInf));
}

TEST(HorizonFailSafe, NaNSpanHidesNothingAndRaisesNothing) {
  OcclusionHorizon h = raised_everywhere();
  for (const AzimuthSpan& nan_span : {AzimuthSpan{kNaN, 1.0}, AzimuthSpan{1.0, kNaN}, AzimuthSpan{kNaN, kNaN},
                                      AzimuthSpan{1.0, 1.5, kNaN}}) {
    EXPECT_FALSE(nan_span.valid());
    EXPECT_EQ(h.min_over(nan_span), -kInf);
    EXPECT_EQ(h.max_over(nan_span), kInf);
    EXPECT_FALSE(h.hides(nan_span, 0.5));
    OcclusionHorizon low(16);
    low.raise(nan_span, 3.0);
    low.restrict_to(nan_span);
    EXPECT_EQ(bins_of(low), std::vector<double>(16, -kInf));
  }
}

TEST(HorizonFailSafe, NaNOrInfiniteSlopeIsNeverHiddenAndNaNRaisesNothing) {
  OcclusionHorizon h = raised_everywhere();
  EXPECT_FALSE(h.hides({1.0, 1.5}, kNaN));
  EXPECT_FALSE(h.hides({1.0, 1.5}, -kInf)) << "-inf is below every bin, but it is not a slope of anything real";
  EXPECT_FALSE(h.hides({1.0, 1.5}, kInf));
  OcclusionHorizon low(16);
  low.raise({0.0, kTwoPi}, kNaN);
  EXPECT_EQ(bins_of(low), std::vector<double>(16, -kInf));
  // A NaN bin assigned (ΔH combines whole horizons) is -inf: it hides nothing.
  std::vector<double> values(16, 2.0);
  values[5] = kNaN;
  low.assign(values);
  EXPECT_EQ(low.bin_value(5), -kInf);
  EXPECT_EQ(low.min_over({0.0, kTwoPi}), -kInf);
  EXPECT_FALSE(low.hides({5 * kTwoPi / 16 + 0.01, 5 * kTwoPi / 16 + 0.02}, 0.0));
  EXPECT_EQ(low.check_invariants(), "");
}

TEST(HorizonFailSafe, HugeAzimuthsAndHugeSlackAreNotCulled) {
  OcclusionHorizon h = raised_everywhere();
  // Ends beyond ±16π (a float-to-integer conversion would overflow): unknown, not reduced.
  for (const AzimuthSpan& huge : {AzimuthSpan{1e300, 1e300 + 1.0}, AzimuthSpan{-1e19, -1e19}, AzimuthSpan{0.0, 1e20},
                                  AzimuthSpan{-kInf, kInf}, AzimuthSpan{60.0, 61.0}}) {
    EXPECT_FALSE(huge.valid()) << huge.begin << " " << huge.end;
    EXPECT_FALSE(h.hides(huge, 0.5));
    OcclusionHorizon low(16);
    low.raise(huge, 3.0);
    EXPECT_EQ(bins_of(low), std::vector<double>(16, -kInf));
  }
  // Within ±16π a span is read wherever it lies (here 2 turns on: bins 2..3).
  EXPECT_TRUE((AzimuthSpan{2 * kTwoPi + 1.0, 2 * kTwoPi + 1.5}.valid()));
  // An unbounded slack reads the whole circle and raises nothing: with one bin still low, a
  // span that would otherwise read only raised bins is not hidden.
  OcclusionHorizon one_low(16);
  one_low.raise({-0.01, 15 * kTwoPi / 16 + 0.01}, 1.0);  // bins 0..14
  EXPECT_TRUE(one_low.hides({1.0, 1.5}, 0.5));
  EXPECT_FALSE(one_low.hides({1.0, 1.5, kInf}, 0.5));
  EXPECT_FALSE(one_low.hides({1.0, 1.5, 1e300}, 0.5));
  OcclusionHorizon low(16);
  low.raise({0.0, kTwoPi - 1e-3, kInf}, 3.0);
  EXPECT_EQ(bins_of(low), std::vector<double>(16, -kInf));
}

TEST(HorizonFailSafe, SlackGrowsWithCoordinateMagnitudeOverDistance) {
  const double eps = std::numeric_limits<double>::epsilon();
  EXPECT_EQ(angular_slack(0.0, 10.0), kAngularSlack);
  EXPECT_EQ(angular_slack(1e9, 1.0), kAngularSlack + 4 * eps * 1e9);
  EXPECT_EQ(angular_slack(5e6, 0.0), kInf);
  EXPECT_TRUE(std::isnan(angular_slack(kNaN, 1.0)));
  // A square 1 m east of an eye at (1e9, 1e9): the span's tangent vertices are sqrt(1.25) m
  // away and their coordinates reach 1e9 + 1.
  const double x = 1e9, y = 1e9;
  const std::vector<Vec2> square{{x + 1, y - 0.5}, {x + 1.5, y - 0.5}, {x + 1.5, y + 0.5}, {x + 1, y + 0.5}};
  const auto far = convex_span(square, {x, y});
  ASSERT_TRUE(far);
  EXPECT_EQ(far->span.slack, angular_slack(x + 1, std::sqrt(1.25)));  // tangent vertices (x + 1, y ± 0.5)
  EXPECT_NEAR(far->span.slack, 7.944e-7, 1e-10);
  // The same square at the origin carries (almost) only the base slack.
  const std::vector<Vec2> local{{1, -0.5}, {1.5, -0.5}, {1.5, 0.5}, {1, 0.5}};
  const auto near = convex_span(local, {0, 0});
  ASSERT_TRUE(near);
  EXPECT_EQ(near->span.slack, angular_slack(1.0, std::sqrt(1.25)));
  EXPECT_LT(near->span.slack, 2 * kAngularSlack);
  // The slack is used when rounding: a shadow ending 1e-7 rad past a bin boundary raises the
  // bin before it with the base slack, not with a slack of 1e-6; a test ending 1e-7 rad before a
  // boundary reads the bin after it only with the larger slack.
  const double w = kTwoPi / 16;
  OcclusionHorizon h(16);
  h.raise({kTwoPi - 0.1, kTwoPi + 2 * w + 1e-7}, 1.0);  // bins 0 and 1
  EXPECT_EQ(h.bin_value(0), 1.0);
  EXPECT_EQ(h.bin_value(1), 1.0);
  h.reset();
  h.raise({kTwoPi - 0.1, kTwoPi + 2 * w + 1e-7, 1e-6}, 1.0);
  EXPECT_EQ(h.bin_value(0), 1.0);
  EXPECT_EQ(h.bin_value(1), -kInf);
  h.reset();
  h.raise({kTwoPi - 0.1, kTwoPi + 2 * w + 1e-7}, 1.0);
  EXPECT_TRUE(h.hides({2 * w - 0.1, 2 * w - 1e-7}, 0.5));
  EXPECT_FALSE(h.hides({2 * w - 0.1, 2 * w - 1e-7, 1e-6}, 0.5)) << "the large slack reaches bin 2";
}

// --- ViewPlaneHorizon (OH(IS)) ------------------------------------------------------------------

ViewPlaneHorizon raised_screen() {
  ViewPlaneHorizon h(64);
  h.reset(1.0);
  h.raise(-2.0, 2.0, 1.0);  // every screen bin to (just under) 1
  return h;
}

TEST(HorizonFailSafe, ViewPlaneControlHidesBelowARaisedScreen) {
  ViewPlaneHorizon h = raised_screen();
  EXPECT_TRUE(h.hides(-0.5, 0.5, 0.5));
  EXPECT_TRUE(h.hides(0.2, 0.2, 0.5));
}

TEST(HorizonFailSafe, ViewPlaneEmptyInvertedAndNaNRangesHideNothing) {
  ViewPlaneHorizon h = raised_screen();
  // An empty extent (no projected point: x_min = +inf, x_max = -inf), an inverted range, NaN.
  EXPECT_FALSE(h.hides(kInf, -kInf, 0.5));
  EXPECT_FALSE(h.hides(0.5, -0.5, 0.5));
  EXPECT_EQ(h.min_over(0.5, -0.5), -kInf);
  EXPECT_FALSE(h.hides(kNaN, 0.5, 0.5));
  EXPECT_FALSE(h.hides(-0.5, kNaN, 0.5));
  EXPECT_FALSE(h.hides(-0.5, 0.5, 0.5, kNaN));
  EXPECT_EQ(h.min_over(kNaN, kNaN), -kInf);
  EXPECT_THROW((void)h.bin_of(kNaN), std::invalid_argument);
  // None of them raises anything.
  ViewPlaneHorizon low(64);
  low.reset(1.0);
  low.raise(0.5, -0.5, 3.0);
  low.raise(kNaN, 0.5, 3.0);
  low.raise(-0.5, kNaN, 3.0);
  low.raise(kInf, -kInf, 3.0);
  low.raise(-0.5, 0.5, 3.0, kNaN);
  for (std::uint32_t b = 1; b < 63; ++b) EXPECT_EQ(low.bin_value(b), -kInf) << "bin " << b;
}

TEST(HorizonFailSafe, ViewPlaneNaNOrInfiniteHeightIsNeverHiddenNorRaises) {
  ViewPlaneHorizon h = raised_screen();
  EXPECT_FALSE(h.hides(-0.5, 0.5, kNaN));
  EXPECT_FALSE(h.hides(-0.5, 0.5, -kInf));
  EXPECT_FALSE(h.hides(-0.5, 0.5, kInf));
  ViewPlaneHorizon low(64);
  low.reset(1.0);
  low.raise(-0.5, 0.5, kNaN);
  low.raise(-0.5, 0.5, kInf);
  for (std::uint32_t b = 1; b < 63; ++b) EXPECT_EQ(low.bin_value(b), -kInf) << "bin " << b;
}

TEST(HorizonFailSafe, ViewPlaneSlackGrowsWithCoordinateRounding) {
  EXPECT_EQ(screen_slack(0.0), kScreenSlack);
  EXPECT_EQ(screen_slack(1e9), kScreenSlack + 4 * std::numeric_limits<double>::epsilon() * 1e9);
  // Half the screen raised: a range in the other half is read there; a range near the middle
  // with a huge rounding is widened onto the low half and is not hidden.
  ViewPlaneHorizon h(64);
  h.reset(1.0);
  h.raise(-2.0, 0.0, 1.0);
  EXPECT_TRUE(h.hides(-0.5, -0.1, 0.5));
  EXPECT_FALSE(h.hides(-0.5, -0.1, 0.5, 1e15));
  // ...and a shadow with a huge rounding raises nothing.
  ViewPlaneHorizon low(64);
  low.reset(1.0);
  low.raise(-0.5, 0.5, 1.0, 1e15);
  for (std::uint32_t b = 1; b < 63; ++b) EXPECT_EQ(low.bin_value(b), -kInf) << "bin " << b;
}

// --- Methods on geometry that overflows ----------------------------------------------------------

Camera level_camera(Vec3 eye, double yaw, double hfov = kPi / 2) {
  Camera c;
  c.position = eye;
  c.yaw = yaw;
  c.hfov = hfov;
  c.vfov = hfov >= kTwoPi ? kPi / 2 : kPi / 3;
  c.far = 1e305;
  return c;
}

// A building outside the loader's limits (a library user may build one): finished, not validated.
Building raw_box(ObjectId id, double x0, double y0, double x1, double y1, double height) {
  Building b;
  b.id = id;
  b.height = height;
  b.footprint = {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}};
  finish_building(b);
  return b;
}

bool holds(const std::vector<ObjectId>& pvs, ObjectId id) { return std::binary_search(pvs.begin(), pvs.end(), id); }

// Every method built on a horizon (the region methods too, with `regions`) keeps `target`.
void expect_not_culled(const Scene& scene, const Camera& camera, ObjectId target, const char* label, bool regions) {
  for (const char* name : {"oh_os_conservative", "oh_os_thesis", "oh_is", "delta_h_guarded", "delta_h_thesis"}) {
    auto method = make_method(name, scene);
    const CullResult r = method->cull(camera);
    EXPECT_TRUE(holds(r.pvs, target)) << label << ": " << name << " culled building " << target;
  }
  if (!regions) return;
  for (const std::string& name : region_method_names()) {
    auto method = make_region_method(name, scene);
    const CullResult r = method->cull_region({camera, 0.25, 0.0});
    EXPECT_TRUE(holds(r.pvs, target)) << label << ": " << name << " culled building " << target;
  }
}

TEST(HorizonFailSafe, OccluderWhoseShadowSlopeOverflowsHidesNothing) {
  // A wall 1e308 m high, 0.5 m ahead: its shadow slope (rise / tangent distance 0.54 m)
  // overflows to +inf. It would hide everything behind it, but an infinite slope is not one to
  // trust. (The region methods divide by the distance plus ε, get a finite slope and may cull:
  // they are not asked here.)
  Scene scene;
  scene.buildings = {raw_box(0, 0.5, -0.2, 0.6, 0.2, 1e308), raw_box(1, 10, -0.5, 11, 0.5, 5)};
  const Camera c = level_camera({0, 0, 1.7}, 0.0);
  {
    auto oh = make_method("oh_os_conservative", scene);
    EXPECT_TRUE(holds(oh->cull(c).pvs, 0));
  }
  expect_not_culled(scene, c, 1, "slope overflow", /*regions=*/false);
}

TEST(HorizonFailSafe, CoordinatesThatOverflowDistancesAreNotCulled) {
  // Far from the origin by 1e300 m: squared distances overflow, spans come out NaN or empty.
  // An eye among them, a wall ahead and a building beyond it that rises above the wall (slope
  // 9000 / 1e300 against 48 / 5e299): visible, whatever the arithmetic makes of it.
  Scene scene;
  const double x = 1e300;
  scene.buildings = {raw_box(0, x, -1e299, x * 1.0000001, 1e299, 50), raw_box(1, x * 1.5, -1e299, x * 1.6, 1e299, 9000)};
  // (Perspective cameras only: a 360-degree camera is bounded by its far distance, and the view
  // volume's own distance test, core/camera.cpp, squares the offsets and overflows.)
  const Camera c = level_camera({x * 0.5, 0, 1.7}, 0.0);
  expect_not_culled(scene, c, 1, "1e300 m", /*regions=*/true);
  Camera pitched = c;
  pitched.pitch = 0.3;
  pitched.roll = 0.2;
  expect_not_culled(scene, pitched, 1, "1e300 m, pitched and rolled", /*regions=*/true);
}

// --- Lattice and sample counts of the from-region methods ---------------------------------------

TEST(HorizonFailSafe, CircleTilingRefusesIndicesBeyondItsLattice) {
  EXPECT_NO_THROW((void)CircleTiling{1.0}.nearest_centre({1e9, 1e9}));
  EXPECT_THROW((void)CircleTiling{1e-9}.nearest_centre({1e9, 1e9}), std::invalid_argument);  // 6.7e17 rows > 2^53
  EXPECT_THROW((void)CircleTiling{1e-12}.nearest_centre({1e9, 0.0}), std::invalid_argument);  // beyond int64
  EXPECT_THROW((void)CircleTiling{1.0}.nearest_centre({kNaN, 0.0}), std::invalid_argument);
  EXPECT_THROW((void)CircleTiling{1e-300}.centres_covering({{0, 0}, {1, 0}, {0, 1}}), std::invalid_argument);
  EXPECT_THROW((void)boundary_samples({{0, 0}, {1, 0}, {0, 1}}, 1e-300), std::invalid_argument);
  EXPECT_THROW((void)boundary_samples({{0, 0}, {kNaN, 0}, {0, 1}}, 1.0), std::invalid_argument);
  EXPECT_EQ(boundary_samples({{0, 0}, {2, 0}, {0, 2}}, 1.0).size(), 4u);  // 1 + 2 + 1 pieces
}

}  // namespace
}  // namespace cullcheck
