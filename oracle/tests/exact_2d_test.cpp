#include "oracle/exact_2d.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "core/errors.hpp"
#include "oracle/ray_oracle.hpp"
#include "test_scenes.hpp"

namespace cullcheck::oracle {
namespace {

using namespace testing;

TEST(Exact2d, BuildingBehindAWiderOneIsHiddenAndOneBesideIsVisibleWithItsExactAngle) {
  const Scene scene = scene_of({box_building(1, 10, -3, 12, 3, 10), box_building(2, 20, -2, 22, 2, 8),
                                box_building(3, 20, 5, 22, 8, 8)});
  const Exact2dResult r = exact_visible_2d(scene, kStreetEast);
  EXPECT_EQ(r.visible, (std::vector<ObjectId>{1, 3}));
  // Building 3 shows from A's corner (10, 3) up to its own corner (20, 8).
  EXPECT_NEAR(r.extents.at(3).angular_extent, std::atan(0.4) - std::atan(0.3), 1e-12);
  EXPECT_NEAR(r.extents.at(3).largest_interval, std::atan(0.4) - std::atan(0.3), 1e-12);
  // A's front wall (x = 10, |y| <= 3) fills 2 atan(0.3); its side walls are seen edge-on or not at all.
  EXPECT_NEAR(r.extents.at(1).largest_interval, 2 * std::atan(0.3), 1e-12);
}

TEST(Exact2d, ClipsExactlyAgainstTheHorizontalWedge) {
  const Scene scene = scene_of({box_building(1, 20, -30, 22, 30, 8), box_building(2, -5, 20, 8, 25, 8)});
  const Camera c = level_camera({0, 0, 1.7}, 0.0, 60 * kDeg);
  const Exact2dResult r = exact_visible_2d(scene, c);
  EXPECT_EQ(r.visible, std::vector<ObjectId>{1});  // building 2 lies left of the wedge
  EXPECT_NEAR(r.extents.at(1).angular_extent, 60 * kDeg, 1e-12);
  // Turned left so the wedge's left edge cuts building 2 at azimuth 90 deg.
  const Camera left = level_camera({0, 0, 1.7}, 60 * kDeg, 60 * kDeg);
  const Exact2dResult l = exact_visible_2d(scene, left);
  EXPECT_EQ(l.visible, (std::vector<ObjectId>{1, 2}));
  EXPECT_NEAR(l.extents.at(2).angular_extent, 90 * kDeg - std::atan2(20.0, 8.0), 1e-12);
}

TEST(Exact2d, OmnidirectionalSeesTheFourSurroundingBuildingsAndMergesAcrossAzimuthZero) {
  const Scene scene = scene_of({box_building(1, 10, -5, 15, 5, 20), box_building(2, -15, -5, -10, 5, 20),
                                box_building(3, -5, 10, 5, 15, 20), box_building(4, -5, -15, 5, -10, 20),
                                box_building(5, 30, -3, 32, 3, 20)});
  const Exact2dResult r = exact_visible_2d(scene, omni_camera({0, 0, 1.7}));
  EXPECT_EQ(r.visible, (std::vector<ObjectId>{1, 2, 3, 4}));
  for (ObjectId id : r.visible) EXPECT_NEAR(r.extents.at(id).largest_interval, 2 * std::atan(0.5), 1e-12) << id;
}

TEST(Exact2d, ThrowsTypedErrorsWhenThePlanViewDoesNotModelTheQuestion) {
  const Scene scene = scene_of({box_building(1, 10, -3, 12, 3, 10), box_building(2, 20, 5, 22, 8, 8)});
  const ExactVisibility2d exact(scene);
  Camera pitched = kStreetEast;
  pitched.pitch = 0.1;
  EXPECT_THROW(exact.visible(pitched), InputError);
  Camera rolled = kStreetEast;
  rolled.roll = -0.1;
  EXPECT_THROW(exact.visible(rolled), InputError);
  Camera high = kStreetEast;
  high.position.z = 8.0;  // building 2 is not taller than the eye
  try {
    exact.visible(high);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.object(), "building 2");
    EXPECT_EQ(e.field(), "height");
  }
  for (Vec2 eye : {Vec2{11, 0}, Vec2{10, 0}, Vec2{10, 3}, Vec2{12, -3}}) {  // inside, on a wall, on corners
    Camera c = kStreetEast;
    c.position = {eye.x, eye.y, 1.7};
    EXPECT_THROW(exact.visible(c), InputError) << eye.x << ", " << eye.y;
  }
}

TEST(Exact2d, ApplicabilityNamesWhyThePlanViewIsNotTheTruth) {
  // From street level the 40 m tower shows over the 5 m block: the plan view would call it hidden.
  const Scene over = scene_of({box_building(1, 10, -10, 12, 10, 5), box_building(2, 30, -2, 32, 2, 40)});
  const Exact2dApplicability a = check_exact_2d(over, kStreetEast);
  EXPECT_FALSE(a.applies);
  EXPECT_NE(a.reason.find("building 1"), std::string::npos) << a.reason;
  EXPECT_EQ(exact_visible_2d(over, kStreetEast).visible, std::vector<ObjectId>{1});
  EXPECT_EQ(RayOracle(over).witness(kStreetEast).witnessed, (std::vector<ObjectId>{1, 2}));

  const Scene equal = scene_of({box_building(1, 10, -10, 12, 10, 20), box_building(2, 30, -2, 32, 2, 20)});
  EXPECT_TRUE(exact_2d_applies(equal, kStreetEast));
  EXPECT_TRUE(exact_2d_applies(equal, omni_camera({0, 0, 1.7})));
  Camera pitched = kStreetEast;
  pitched.pitch = 0.01;
  EXPECT_FALSE(exact_2d_applies(equal, pitched));
  Camera short_far = kStreetEast;
  short_far.far = 20;
  EXPECT_FALSE(exact_2d_applies(equal, short_far));
  Camera on_roof = kStreetEast;
  on_roof.position.z = 20;
  EXPECT_FALSE(exact_2d_applies(equal, on_roof));
}

TEST(Exact2d, EyeOnTriangulationDiagonalsAndFarOutsideTheScene) {
  // Four blocks around a crossing: the eye at (15, 15) lies on the diagonals joining opposite
  // corners, and (15, 5) on the segment from (10, 0) to (20, 10), where a triangulation edge
  // can pass exactly through it.
  const Scene scene = scene_of({box_building(1, 0, 0, 10, 10, 20), box_building(2, 20, 0, 30, 10, 20),
                                box_building(3, 0, 20, 10, 30, 20), box_building(4, 20, 20, 30, 30, 20)});
  const ExactVisibility2d exact(scene);
  const RayOracle rays(scene);
  for (Vec2 eye : {Vec2{15, 15}, Vec2{15, 5}, Vec2{15, 25}, Vec2{5, 15}}) {
    const Camera c = omni_camera({eye.x, eye.y, 1.7});
    const Exact2dResult r = exact.visible(c);
    EXPECT_EQ(r.visible, (std::vector<ObjectId>{1, 2, 3, 4})) << eye.x << ", " << eye.y;
    EXPECT_EQ(rays.witness(c).witnessed, r.visible) << eye.x << ", " << eye.y;
  }
  // The exact structure is built around the scene; an eye 100 km away gets a wider frame.
  // Looking down the street y in (10, 20), blocks 2 and 4 show their street walls, at about
  // 5e-9 rad each.
  const Camera distant = level_camera({-1e5, 15, 1.7}, 0.0, 1 * kDeg);
  const Exact2dResult d = exact.visible(distant);
  EXPECT_EQ(d.visible, (std::vector<ObjectId>{1, 2, 3, 4}));
  EXPECT_LT(d.extents.at(2).angular_extent, 1e-8);
}

TEST(Exact2d, EmptySceneShowsNothing) {
  const Scene empty;
  EXPECT_TRUE(exact_visible_2d(empty, omni_camera({0, 0, 1.7})).visible.empty());
  EXPECT_TRUE(exact_2d_applies(empty, omni_camera({0, 0, 1.7})));
}

// A city of 500 buildings: the exact set is the ray oracle's witnessed set or a superset (every
// witness ray is a real sight line, the plan view is the truth here), and holds what the 360-degree
// eye sees of its neighbourhood. Speed is BM_Exact2dFiveHundredBuildings's (oracle_bench), not a
// test's: a time limit here would fail on a loaded machine and pass a slow oracle on a fast one.
TEST(Exact2d, FiveHundredBuildingsAgreeWithTheRayOracle) {
  const Scene scene = jittered_grid_500();
  const Camera eye = omni_camera(kJitteredGridEye);
  ASSERT_TRUE(exact_2d_applies(scene, eye));
  const ExactVisibility2d exact(scene);
  const Exact2dResult r = exact.visible(eye);
  EXPECT_GT(r.visible.size(), 10u);
  EXPECT_GT(r.visibility_polygon_edges, r.visible.size());
  const std::vector<ObjectId> witnessed = RayOracle(scene).witness(eye).witnessed;
  EXPECT_GT(witnessed.size(), 10u);
  EXPECT_TRUE(std::includes(r.visible.begin(), r.visible.end(), witnessed.begin(), witnessed.end()))
      << witnessed.size() << " witnessed, " << r.visible.size() << " exactly visible";
}

}  // namespace
}  // namespace cullcheck::oracle
