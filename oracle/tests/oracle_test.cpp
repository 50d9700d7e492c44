#include "oracle/oracle.hpp"

#include <gtest/gtest.h>

#include "test_scenes.hpp"

namespace cullcheck::oracle {
namespace {

using namespace testing;

TEST(Oracle, PicksExact2dWhenThePlanViewIsTheTruthAndSaysSo) {
  const Scene scene = scene_of({box_building(1, 10, -3, 12, 3, 20), box_building(2, 20, -2, 22, 2, 20),
                                box_building(3, 20, 5, 22, 8, 20)});
  const Oracle oracle(scene);
  const OracleAnswer a = oracle.visible_set(level_camera({0, 0, 1.7}, 0.0));
  EXPECT_EQ(a.model, kModelExact2d);
  EXPECT_TRUE(a.exact);
  EXPECT_TRUE(a.exact_2d.has_value());
  EXPECT_FALSE(a.sampling.has_value());
  EXPECT_EQ(a.visible, (std::vector<ObjectId>{1, 3}));
  OracleOptions forced;
  forced.allow_exact_2d = false;
  const OracleAnswer b = oracle.visible_set(level_camera({0, 0, 1.7}, 0.0), forced);
  EXPECT_EQ(b.model, kModelRaySampling3d);
  EXPECT_EQ(b.visible, a.visible);
}

TEST(Oracle, FallsBackToRaySamplingAndNamesTheReason) {
  const Scene scene = scene_of({box_building(1, 10, -10, 12, 10, 5), box_building(2, 30, -2, 32, 2, 40)});
  const Oracle oracle(scene);
  const OracleAnswer level = oracle.visible_set(level_camera({0, 0, 1.7}, 0.0));
  EXPECT_EQ(level.model, kModelRaySampling3d);
  EXPECT_FALSE(level.exact);
  EXPECT_NE(level.why.find("seen over"), std::string::npos) << level.why;
  EXPECT_EQ(level.visible, (std::vector<ObjectId>{1, 2}));
  Camera pitched = level_camera({0, 0, 1.7}, 0.0);
  pitched.pitch = 0.2;
  const OracleAnswer p = oracle.visible_set(pitched);
  EXPECT_EQ(p.model, kModelRaySampling3d);
  EXPECT_NE(p.why.find("level"), std::string::npos) << p.why;
  ASSERT_TRUE(p.sampling.has_value());
  EXPECT_EQ(p.visible, p.sampling->witnessed);
}

}  // namespace
}  // namespace cullcheck::oracle
