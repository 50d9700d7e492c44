// The hard-case classifier of case_coverage.hpp fires on constructed cases of each kind and stays
// silent on their near misses (pinned scenes and cameras; the oracle decides what is seen).
#include <gtest/gtest.h>

#include "core/scene_io.hpp"
#include "oracle/oracle.hpp"
#include "properties/case_coverage.hpp"
#include "properties/property_oracle.hpp"

namespace cullcheck {
namespace {

Building box(ObjectId id, double x0, double y0, double x1, double y1, double h) {
  Building b;
  b.id = id;
  b.height = h;
  b.footprint = {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}};
  validate_and_finish(b);
  return b;
}

// Two 20 m walls 10-20 m east of the eye with a gap of `gap` metres on the view axis, and a
// 15 m building 40-50 m east that only the gap shows (lower than the walls, so the oracle samples
// rays: exact_2d keeps none, oracle/exact_2d.hpp).
Scene gap_scene(double gap) {
  Scene s;
  s.buildings = {box(0, 10, -10, 20, -gap / 2, 20), box(1, 10, gap / 2, 20, 10, 20), box(2, 40, -5, 50, 5, 15)};
  return s;
}

Camera eye_at(double x, double y, double z) {
  Camera c;
  c.position = {x, y, z};
  return c;  // yaw 0: looking east, 60 x 45 degrees
}

std::array<bool, 4> features(const Scene& scene, const Camera& camera) {
  const oracle::OracleAnswer seen = oracle::Oracle(scene).visible_set(camera, property_oracle());
  return hard_case_features(scene, camera, seen, nullptr, nullptr);
}

TEST(CaseCoverage, SeenThroughAGapNarrowerThanOneMetre) {
  const Scene narrow = gap_scene(0.6);
  const oracle::OracleAnswer seen = oracle::Oracle(narrow).visible_set(eye_at(0, 0, 1.7), property_oracle());
  ASSERT_EQ(seen.model, oracle::kModelRaySampling3d);
  ASSERT_EQ(seen.visible, (std::vector<ObjectId>{0, 1, 2}));
  EXPECT_TRUE(features(narrow, eye_at(0, 0, 1.7))[int(HardCase::narrow_gap)]);
  // A 3 m gap shows the same building, but not through a narrow gap.
  EXPECT_FALSE(features(gap_scene(3.0), eye_at(0, 0, 1.7))[int(HardCase::narrow_gap)]);
  // Above the roofs the rays pass over the walls, which then bound no gap.
  Camera above = eye_at(0, 0, 60);
  above.pitch = -0.6;
  EXPECT_FALSE(features(narrow, above)[int(HardCase::narrow_gap)]);
}

TEST(CaseCoverage, EyeWithinOneMetreOfAWall) {
  const Scene s = gap_scene(3.0);
  EXPECT_TRUE(features(s, eye_at(9.5, 5, 1.7))[int(HardCase::eye_near_wall)]);
  EXPECT_FALSE(features(s, eye_at(8.9, 5, 1.7))[int(HardCase::eye_near_wall)]);
  EXPECT_FALSE(features(s, eye_at(9.5, 5, 25.0))[int(HardCase::eye_near_wall)]);  // above the roof: no wall
}

TEST(CaseCoverage, PitchOrRollBeyondThirtyDegrees) {
  const Scene s = gap_scene(3.0);
  const oracle::OracleAnswer none;
  auto steep = [&](double pitch_deg, double roll_deg, double hfov) {
    Camera c = eye_at(0, 0, 1.7);
    c.pitch = pitch_deg * kPi / 180, c.roll = roll_deg * kPi / 180, c.hfov = hfov;
    return hard_case_features(s, c, none, nullptr, nullptr)[int(HardCase::steep)];
  };
  EXPECT_TRUE(steep(31, 0, kPi / 3));
  EXPECT_FALSE(steep(29, 0, kPi / 3));
  EXPECT_TRUE(steep(-45, 0, kPi / 3));
  EXPECT_TRUE(steep(0, -150, kPi / 3));
  EXPECT_FALSE(steep(0, 359, kPi / 3));      // 359 degrees is a roll of -1
  EXPECT_FALSE(steep(40, 40, kTwoPi));       // 360 degrees: pitch and roll are ignored
}

TEST(CaseCoverage, HorizonCullsBeyondTheFrustum) {
  const Scene s = gap_scene(3.0);
  const oracle::OracleAnswer none;
  const std::vector<ObjectId> frustum{0, 1, 2}, horizon{0, 1};
  EXPECT_TRUE(hard_case_features(s, eye_at(0, 0, 1.7), none, &horizon, &frustum)[int(HardCase::horizon_beyond_frustum)]);
  EXPECT_FALSE(hard_case_features(s, eye_at(0, 0, 1.7), none, &frustum, &frustum)[int(HardCase::horizon_beyond_frustum)]);
  EXPECT_FALSE(hard_case_features(s, eye_at(0, 0, 1.7), none, nullptr, &frustum)[int(HardCase::horizon_beyond_frustum)]);
}

TEST(CaseCoverage, SharesAndSummary) {
  HardCaseCoverage c;
  c.add({true, false, true, false});
  c.add({true, true, false, false});
  EXPECT_DOUBLE_EQ(c.share(HardCase::horizon_beyond_frustum), 1.0);
  EXPECT_DOUBLE_EQ(c.share(HardCase::narrow_gap), 0.5);
  EXPECT_EQ(c.summary("m"), "m over 2 cases: horizon culls beyond the frustum 100.0%, visible through a gap < 1 m 50.0%, "
                            "eye within 1 m of a wall 50.0%, pitch or roll > 30 degrees 0.0%");
}

}  // namespace
}  // namespace cullcheck
