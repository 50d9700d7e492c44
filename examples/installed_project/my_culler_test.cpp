// A user's test of their own culler against cullcheck's oracle, through the installed package.
#include <gtest/gtest.h>

#include <cullcheck/gate.hpp>

#include "core/formats/mesh_formats.hpp"
#include "core/scene_io.hpp"

namespace {

// Two boxes in a row along +x; the far one (30 m) shows above the near one (5 m) from 1.7 m.
cullcheck::Scene two_boxes() {
  cullcheck::Scene scene;
  scene.buildings.push_back(cullcheck::box_building(1, 20, -5, 25, 5, 5));
  scene.buildings.push_back(cullcheck::box_building(2, 40, -5, 45, 5, 30));
  return scene;
}

cullcheck::Camera eye() {
  cullcheck::Camera c;
  c.position = {0, 0, 1.7};
  c.yaw = 0.0;
  return c;
}

// "My culler": culls the second object (the bug under test), or nothing.
std::vector<cullcheck::ObjectId> my_culler(bool buggy) { return buggy ? std::vector<cullcheck::ObjectId>{1} : std::vector<cullcheck::ObjectId>{1, 2}; }

TEST(MyCuller, KeepsWhatIsVisible) {
  const cullcheck::Gate gate(two_boxes());
  const cullcheck::FrameVerdict v = gate.check_conservative(eye(), my_culler(false));
  EXPECT_TRUE(v.passed) << v.message;
  EXPECT_EQ(v.witnessed, 2u);
  EXPECT_EQ(v.misdrawn_pixels, 0u);
}

TEST(MyCuller, TheGateCatchesAMissWithAReplay) {
  const cullcheck::Gate gate(two_boxes());
  const cullcheck::FrameVerdict v = gate.check_conservative(eye(), my_culler(true));
  ASSERT_FALSE(v.passed);
  EXPECT_EQ(v.missed, std::vector<cullcheck::ObjectId>{2});
  EXPECT_GT(v.misdrawn_pixels, 0u);
  EXPECT_NE(v.message.find("replay: cullcheck gate"), std::string::npos) << v.message;
  EXPECT_NE(v.message.find("--visible '[1]'"), std::string::npos) << v.message;
}

TEST(MyCuller, ReadsTheSceneAsGltf) {
  const std::string path = testing::TempDir() + "/two_boxes.glb";
  cullcheck::formats::write_glb(two_boxes(), path);
  const cullcheck::Gate gate(path);
  EXPECT_EQ(gate.scene().object_count(), 2u);
  const cullcheck::FrameVerdict v = gate.check_approximate(eye(), my_culler(true), 1000000);
  EXPECT_TRUE(v.passed) << v.message;  // within a generous pixel budget
  EXPECT_FALSE(gate.check_approximate(eye(), my_culler(true), 10).passed);
}

}  // namespace
