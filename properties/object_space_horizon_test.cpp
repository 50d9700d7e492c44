// OH(OS) on hand-built scenes whose visible sets are known from their geometry, including the
// published shadow-elevation rule's counterexample (a wide low slab seen from above).
#include <gtest/gtest.h>

#include <algorithm>

#include "core/scene_io.hpp"
#include "engine/horizon/object_space_horizon.hpp"
#include "engine/method.hpp"

namespace cullcheck {
namespace {

Camera level_camera(Vec3 eye, double yaw_degrees, double hfov_degrees = 90) {
  Camera c;
  c.position = eye;
  c.yaw = yaw_degrees * kPi / 180;
  c.hfov = hfov_degrees * kPi / 180;
  c.vfov = 60 * kPi / 180;
  c.far = 1e4;
  return c;
}

bool contains(const std::vector<ObjectId>& pvs, ObjectId id) { return std::binary_search(pvs.begin(), pvs.end(), id); }

TEST(ObjectSpaceHorizon, TallWallHidesWhatIsBehindIt) {
  Scene scene;
  scene.buildings = {box_building(0, 10, -5, 12, 5, 20), box_building(1, 30, -2, 35, 2, 10), box_building(2, 30, 20, 35, 25, 5),
                     box_building(3, -20, -2, -15, 2, 10)};
  for (const char* name : {"oh_os_thesis", "oh_os_conservative"}) {
    auto method = make_method(name, scene);
    const CullResult r = method->cull(level_camera({0, 0, 1.7}, 0));
    EXPECT_TRUE(contains(r.pvs, 0)) << name;
    EXPECT_FALSE(contains(r.pvs, 1)) << name << ": behind the wall";
    EXPECT_TRUE(contains(r.pvs, 2)) << name << ": beside the wall, inside the frustum";
    EXPECT_FALSE(contains(r.pvs, 3)) << name << ": behind the camera";
    EXPECT_GT(r.stats.occluders_applied, 0u);
  }
  auto frustum = make_method("frustum", scene);
  EXPECT_EQ(frustum->cull(level_camera({0, 0, 1.7}, 0)).pvs, (std::vector<ObjectId>{0, 1, 2}));
}

TEST(ObjectSpaceHorizon, OmnidirectionalSeesAllAround) {
  Scene scene;
  scene.buildings = {box_building(0, 10, -2, 12, 2, 8), box_building(1, -12, -2, -10, 2, 8), box_building(2, -2, 10, 2, 12, 8),
                     box_building(3, -2, -12, 2, -10, 8), box_building(4, 30, -1, 32, 1, 4)};
  Camera c = level_camera({0, 0, 1.7}, 0);
  c.hfov = kTwoPi;
  for (const char* name : {"frustum", "oh_os_thesis", "oh_os_conservative"}) {
    const CullResult r = make_method(name, scene)->cull(c);
    for (ObjectId id : {0u, 1u, 2u, 3u}) EXPECT_TRUE(contains(r.pvs, id)) << name << " building " << id;
    if (std::string(name) != "frustum") {
      EXPECT_FALSE(contains(r.pvs, 4)) << name << ": hidden behind building 0";
    }
  }
}

TEST(ObjectSpaceHorizon, EyeInsideAFootprintNeverCullsThatBuilding) {
  Scene scene;
  scene.buildings = {box_building(0, -5, -5, 5, 5, 10), box_building(1, 20, -5, 25, 5, 30)};
  Camera c = level_camera({0, 0, 12}, 0);  // standing on the roof of building 0
  c.pitch = -0.5;
  for (const char* name : {"oh_os_thesis", "oh_os_conservative"}) {
    const CullResult r = make_method(name, scene)->cull(c);
    EXPECT_TRUE(contains(r.pvs, 0)) << name;
    EXPECT_TRUE(contains(r.pvs, 1)) << name;
  }
}

// The thesis takes a shadow's elevation from the lower of its two tangent vertices (ch. 3.1.2).
// For a roof below the eye, the silhouette is the roof's far edge, which can be nearer than the
// tangent vertices: here a 1 m deep, 40 m wide slab 20 m ahead, 10 m tall, seen from 30 m up.
// A 1 m kiosk 40 m ahead shows above the slab's far edge (the sight line clears it by 4.8 m),
// yet lies below the thesis's shadow.
TEST(ObjectSpaceHorizon, ThesisShadowRuleHidesWhatShowsAboveALowWideRoof) {
  Scene scene;
  scene.buildings = {box_building(0, 20, -20, 21, 20, 10), box_building(1, 40, -0.5, 41, 0.5, 1)};
  Camera c = level_camera({0, 0, 30}, 0, 60);
  c.pitch = -0.6;
  // Sight line from the eye to the kiosk's near top edge, at the slab's far wall:
  const double height_at_far_wall = 30 + (1.0 - 30) * 21 / 40;
  ASSERT_GT(height_at_far_wall, 10.0);
  EXPECT_FALSE(contains(make_method("oh_os_thesis", scene)->cull(c).pvs, 1));
  EXPECT_TRUE(contains(make_method("oh_os_conservative", scene)->cull(c).pvs, 1));
}

TEST(ObjectSpaceHorizon, PitchAndRollMapTheFrustumToItsAzimuths) {
  Scene scene;
  scene.buildings = {box_building(0, 10, -2, 12, 2, 8), box_building(1, -12, -2, -10, 2, 8)};
  Camera c = level_camera({0, 0, 1.7}, 0, 60);
  c.pitch = 80 * kPi / 180;  // looking almost straight up
  c.roll = 0.7;
  for (const char* name : {"frustum", "oh_os_thesis", "oh_os_conservative"}) {
    const CullResult r = make_method(name, scene)->cull(c);
    EXPECT_FALSE(contains(r.pvs, 1)) << name << ": behind";
  }
  c.pitch = kPi / 2;  // straight up: the pyramid contains the zenith, every azimuth is covered
  auto oh = make_method("oh_os_conservative", scene);
  const CullResult r = oh->cull(c);
  EXPECT_EQ(r.pvs, make_method("frustum", scene)->cull(c).pvs);
}

}  // namespace
}  // namespace cullcheck
