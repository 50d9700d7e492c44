// Numerical extremes (design: "Numerical extremes (each a test)"): each case runs every method
// claimed conservative and holds it to the oracle; none may crash, none may cull what the
// oracle sees. (Float versus double: the engine offers double only, so there is no pair to test.)
#include <gtest/gtest.h>

#include <cmath>

#include "core/errors.hpp"
#include "core/scene_io.hpp"
#include "engine/method.hpp"
#include "oracle/oracle.hpp"

namespace cullcheck {
namespace {

Camera camera_at(Vec3 eye, double yaw, double pitch = 0.0, double hfov = kPi / 2, double vfov = kPi / 3) {
  Camera c;
  c.position = eye;
  c.yaw = yaw;
  c.pitch = pitch;
  c.hfov = hfov;
  c.vfov = vfov;
  return c;
}

// Holds every conservative method to the oracle; returns the oracle's set for further checks.
std::vector<ObjectId> expect_conservative(const Scene& scene, const Camera& camera, const std::string& label) {
  const oracle::Oracle truth(scene);
  oracle::OracleOptions options;
  options.sampling.spacing_m = 0.5;
  const oracle::OracleAnswer seen = truth.visible_set(camera, options);
  for (const std::string& name : method_names()) {
    auto method = make_method(name, scene);
    if (!method->claims_conservative()) continue;
    const CullResult r = method->cull(camera);
    for (ObjectId id : seen.visible)
      EXPECT_TRUE(std::binary_search(r.pvs.begin(), r.pvs.end(), id))
          << label << ": " << name << " culled building " << id << " which the oracle sees; camera "
          << camera_to_json_text(camera);
  }
  return seen.visible;
}

// A street with buildings on both sides and a row behind, used by several cases.
Scene street(double offset_x = 0.0, double offset_y = 0.0) {
  Scene s;
  ObjectId id = 0;
  for (int i = 0; i < 6; ++i) {
    const double x = offset_x + i * 12.0;
    s.buildings.push_back(box_building(id++, x, offset_y + 8, x + 10, offset_y + 20, 6.0 + 3 * (i % 3)));
    s.buildings.push_back(box_building(id++, x, offset_y - 20, x + 10, offset_y - 8, 15.0 - 2 * (i % 4)));
    s.buildings.push_back(box_building(id++, x + 2, offset_y + 26, x + 8, offset_y + 30, 25.0));
  }
  return s;
}

TEST(NumericalExtremes, CoordinatesOffsetByTenMillionMetres) {
  Scene far = street(1.0e7, 1.0e7);
  far = scene_from_json_text(scene_to_json_text(far));  // loading rebases it
  ASSERT_GT(std::abs(far.origin.x), 1e6);
  const Scene near = street();
  for (double yaw : {0.0, 0.4, kPi}) {
    const Vec3 eye_far{1.0e7 + 5 - far.origin.x, 1.0e7 - far.origin.y, 1.7};
    const auto seen_far = expect_conservative(far, camera_at(eye_far, yaw), "offset 1e7");
    const auto seen_near = expect_conservative(near, camera_at({5, 0, 1.7}, yaw), "at origin");
    EXPECT_EQ(seen_far, seen_near) << "yaw " << yaw;
    EXPECT_EQ(make_method("oh_os_conservative", far)->cull(camera_at(eye_far, yaw)).pvs,
              make_method("oh_os_conservative", near)->cull(camera_at({5, 0, 1.7}, yaw)).pvs);
  }
}

TEST(NumericalExtremes, OneMillimetreAndTenKilometreBuildings) {
  Scene s;
  s.buildings = {box_building(0, 10, -0.0005, 10.001, 3, 20),    // 1 mm thin slab
                 box_building(1, 30, -5000, 40, 5000, 30),       // 10 km long wall
                 box_building(2, 20, -1, 22, 1, 4), box_building(3, 60, -2, 64, 2, 50)};
  for (double yaw : {0.0, 0.1, -0.1 + kTwoPi})
    for (double z : {1.7, 35.0, 80.0}) expect_conservative(s, camera_at({0, 0, z}, yaw, z > 30 ? -0.4 : 0.0), "mm and km");
}

TEST(NumericalExtremes, OccluderExactlyAtEyeHeight) {
  Scene s;
  s.buildings = {box_building(0, 10, -5, 11, 5, 1.7), box_building(1, 20, -1, 21, 1, 1.7), box_building(2, 30, -1, 31, 1, 1.0),
                 box_building(3, 40, -1, 41, 1, 2.5)};
  const auto seen = expect_conservative(s, camera_at({0, 0, 1.7}, 0.0), "eye height");
  EXPECT_TRUE(std::binary_search(seen.begin(), seen.end(), 3u));  // shows above the eye-height wall
}

TEST(NumericalExtremes, ViewpointOnAWallOnACornerAndInsideABuilding) {
  const Scene s = street();
  const Vec3 on_wall{5, 8, 1.7}, on_corner{0, 8, 1.7}, inside{5, 14, 1.7};
  for (const Vec3& eye : {on_wall, on_corner, inside})
    for (double yaw : {0.0, kPi / 2, kPi, 3 * kPi / 2}) expect_conservative(s, camera_at(eye, yaw), "eye on or in a building");
}

TEST(NumericalExtremes, AzimuthExactlyZeroPiAndJustBelowTwoPi) {
  Scene s;
  // Buildings straddling azimuth 0 (east), at π (west), and at the wrap from both sides.
  s.buildings = {box_building(0, 10, -2, 12, 2, 10), box_building(1, 30, -6, 32, 6, 20), box_building(2, -12, -2, -10, 2, 10),
                 box_building(3, -32, -6, -30, 6, 20), box_building(4, 20, -0.5, 21, 0.0, 30), box_building(5, 20, 0.0, 21, 0.5, 30)};
  for (double yaw : {0.0, kPi, std::nextafter(kTwoPi, 0.0), kPi / 2})
    for (double hfov : {kPi / 2, kTwoPi}) expect_conservative(s, camera_at({0, 0, 1.7}, yaw, 0.0, hfov), "azimuth wrap");
}

TEST(NumericalExtremes, CollinearAndTouchingWalls) {
  Scene s;
  s.buildings = {box_building(0, 10, -5, 12, 0, 10), box_building(1, 10, 0, 12, 5, 10),  // share the wall y = 0
                 box_building(2, 12, -5, 14, 5, 8),                           // touches both
                 box_building(3, 20, -0.5, 21, 0.5, 30),                      // behind the seam
                 box_building(4, 10, 5, 12, 10, 12)};                         // collinear with 0 and 1
  for (double y : {0.0, 1e-9, -1e-9, 5.0}) expect_conservative(s, camera_at({0, y, 1.7}, 0.0), "touching walls");
}

TEST(NumericalExtremes, SliverFootprintsWorkAndZeroAreaIsRefused) {
  Scene s;
  Building sliver;
  sliver.id = 0;
  sliver.height = 20;
  sliver.footprint = {{10, 0}, {30, 0.001}, {10, 0.002}};  // 20 m long, 2 mm wide triangle
  validate_and_finish(sliver);
  s.buildings = {sliver, box_building(1, 40, -1, 41, 1, 5)};
  expect_conservative(s, camera_at({0, 0.001, 1.7}, 0.0), "sliver");
  expect_conservative(s, camera_at({0, 10, 1.7}, -kPi / 4), "sliver, oblique");
  Building flat;
  flat.id = 2;
  flat.height = 5;
  flat.footprint = {{0, 0}, {1, 1}, {2, 2}};
  EXPECT_THROW(validate_and_finish(flat), InputError);
}

TEST(NumericalExtremes, FieldOfViewNearZeroAndFullCircle) {
  const Scene s = street();
  const double tiny = 1e-4 * kPi / 180;  // 0.0001 degrees
  expect_conservative(s, camera_at({5, 0, 1.7}, 0.0, 0.0, tiny, tiny), "fov 0.0001 degrees");
  expect_conservative(s, camera_at({5, 0, 1.7}, kPi / 2, 0.0, tiny, tiny), "fov 0.0001 degrees at a wall");
  expect_conservative(s, camera_at({5, 0, 1.7}, 0.0, 0.0, kTwoPi), "fov 360 degrees");
  expect_conservative(s, camera_at({5, 0, 40.0}, 0.0, 0.0, kTwoPi), "fov 360 degrees above the roofs");
  EXPECT_THROW(validate(camera_at({5, 0, 1.7}, 0.0, 0.0, kPi)), InputError);  // 180: neither kind
}

TEST(NumericalExtremes, PitchPlusMinusNinetyDegrees) {
  const Scene s = street();
  for (double pitch : {kPi / 2, -kPi / 2})
    for (double roll : {0.0, 1.0})
      for (double z : {1.7, 40.0}) {
        Camera c = camera_at({5, 0, z}, 0.3, pitch);
        c.roll = roll;
        expect_conservative(s, c, "pitch +-90");
      }
}

// Geometry nearer than the near plane is clipped and hides nothing: a thin slab running away
// from the eye, whose first half metre is clipped, must not hide what is seen past its clipped
// end (found by hand; the engine now skips occluders that may reach in front of the near plane).
TEST(NumericalExtremes, OccluderReachingInFrontOfTheNearPlane) {
  Scene s;
  Building slab;
  slab.id = 0;
  slab.height = 10;
  slab.footprint = {{0.05, -0.02}, {3, 2.93}, {2.999, 2.931}, {0.049, -0.019}};
  validate_and_finish(slab);
  s.buildings = {slab, box_building(1, 20, 8, 21, 12, 10)};
  for (double yaw : {0.45, 0.6}) {
    Camera c = camera_at({0, 0, 1.7}, yaw, 0.0, 1.2, 0.8);
    c.near = 0.5;
    const auto seen = expect_conservative(s, c, "near-plane clipping");
    EXPECT_TRUE(std::binary_search(seen.begin(), seen.end(), 1u));
  }
}

}  // namespace
}  // namespace cullcheck
