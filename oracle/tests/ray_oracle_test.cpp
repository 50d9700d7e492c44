#include "oracle/ray_oracle.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <nlohmann/json.hpp>

#include "core/errors.hpp"
#include "test_scenes.hpp"

namespace cullcheck::oracle {
namespace {

using namespace testing;

// Eye at street level, looking east (+x).
const Camera kStreetEast = level_camera({0, 0, 1.7}, 0.0);

TEST(RayOracle, BuildingBehindAWiderLowerOneIsNotWitnessed) {
  // A (10 m high, 6 m wide) hides B (8 m high) completely: B's top is at elevation 17.5 deg,
  // A's front top edge at 39.7 deg, and in plan B lies inside A's shadow.
  const Scene scene = scene_of({box_building(1, 10, -3, 12, 3, 10), box_building(2, 20, -2, 22, 2, 8)});
  const OracleResult r = RayOracle(scene).witness(kStreetEast);
  EXPECT_EQ(r.witnessed, std::vector<ObjectId>{1});
  EXPECT_EQ(r.candidates, 2u);
}

TEST(RayOracle, BuildingBesideTheOccluderIsWitnessed) {
  const Scene scene = scene_of({box_building(1, 10, -3, 12, 3, 10), box_building(2, 20, 5, 22, 8, 8)});
  const OracleResult r = RayOracle(scene).witness(kStreetEast);
  EXPECT_EQ(r.witnessed, (std::vector<ObjectId>{1, 2}));
}

TEST(RayOracle, TallBuildingBehindALowOneIsWitnessedOverIt) {
  // A is 5 m high and 20 m wide; B behind it is 40 m high: from 1.7 m its upper part shows
  // above A (elevations 18.3 deg to 30 deg, the top of the 60 deg vertical fov).
  const Scene scene = scene_of({box_building(1, 10, -10, 12, 10, 5), box_building(2, 30, -2, 32, 2, 40)});
  const OracleResult r = RayOracle(scene).witness(kStreetEast);
  EXPECT_EQ(r.witnessed, (std::vector<ObjectId>{1, 2}));
  EXPECT_GT(r.witnesses.at(2).hit_point.z, 5.0);
}

TEST(RayOracle, BuildingOutsideTheFrustumIsNotWitnessed) {
  const Scene scene = scene_of({box_building(1, 10, -3, 12, 3, 10),     // ahead
                                box_building(2, -30, -3, -20, 3, 50),   // behind the eye
                                box_building(3, 10, 40, 20, 50, 50),    // left, beyond hfov/2
                                box_building(4, 50, -1, 52, 1, 1000)}); // ahead, beyond far
  Camera c = kStreetEast;
  c.far = 40;  // building 4 lies beyond far
  const OracleResult r = RayOracle(scene).witness(c);
  EXPECT_EQ(r.witnessed, std::vector<ObjectId>{1});
  EXPECT_EQ(r.candidates, 1u);
}

TEST(RayOracle, NearPlaneClipsWhatLiesBeforeIt) {
  // A thin wall 0.5 m ahead lies before a 1 m near plane: it is clipped, so it hides nothing.
  const Scene scene = scene_of({box_building(1, 0.5, -50, 0.6, 50, 100), box_building(2, 20, -2, 22, 2, 8)});
  Camera c = kStreetEast;
  c.near = 1.0;
  const OracleResult r = RayOracle(scene).witness(c);
  EXPECT_EQ(r.witnessed, std::vector<ObjectId>{2});
}

TEST(RayOracle, CameraLookingDownSeesARoof) {
  const Scene scene = scene_of({box_building(1, -5, -5, 5, 5, 10), box_building(2, 200, 200, 210, 210, 10)});
  Camera c;
  c.position = {0, 0, 50};
  c.pitch = -kPi / 2;
  c.hfov = c.vfov = 60 * kDeg;
  const OracleResult r = RayOracle(scene).witness(c);
  ASSERT_EQ(r.witnessed, std::vector<ObjectId>{1});
  EXPECT_NEAR(r.witnesses.at(1).hit_point.z, 10.0, 1e-9);  // on the roof plane
}

TEST(RayOracle, OmnidirectionalCameraSeesAllFourSurroundingBuildings) {
  const Scene scene = scene_of({box_building(1, 10, -5, 15, 5, 20), box_building(2, -15, -5, -10, 5, 20),
                                box_building(3, -5, 10, 5, 15, 20), box_building(4, -5, -15, 5, -10, 20),
                                box_building(5, 30, -3, 32, 3, 15)});  // hidden behind 1
  const OracleResult r = RayOracle(scene).witness(omni_camera({0, 0, 1.7}));
  EXPECT_EQ(r.witnessed, (std::vector<ObjectId>{1, 2, 3, 4}));
}

TEST(RayOracle, WitnessRaysReallyHitTheirBuildingInsideTheViewVolume) {
  for (std::uint64_t seed : {11, 12, 13}) {
    const RandomCity city = random_city(seed);
    const RayOracle oracle(city.scene);
    const OracleResult r = oracle.witness(city.camera);
    ASSERT_FALSE(r.witnessed.empty());
    for (const auto& [id, ray] : r.witnesses) {
      const RayOracle::Replay replay = oracle.replay(ray, city.camera);
      ASSERT_TRUE(replay.hit.has_value()) << "seed " << seed << ": " << describe(ray);
      EXPECT_EQ(*replay.hit, id) << "seed " << seed << ": " << describe(ray);
      EXPECT_TRUE(replay.in_view_volume) << "seed " << seed << ": " << describe(ray);
      EXPECT_NEAR(replay.t_hit, ray.t_hit, 1e-9 * (1 + ray.t_hit));
      EXPECT_TRUE(ViewVolume(city.camera).contains(ray.hit_point));
      EXPECT_NEAR(length(ray.direction), 1.0, 1e-12);
    }
  }
}

TEST(RayOracle, RunsAreDeterministicAndIndependentOfThreadCount) {
  const RandomCity city = random_city(21);
  SamplingOptions one, two;
  one.threads = 1;
  two.threads = 2;
  const RayOracle oracle(city.scene);
  const OracleResult a = oracle.witness(city.camera, two), b = oracle.witness(city.camera, two);
  const OracleResult c = RayOracle(city.scene).witness(city.camera, one);
  for (const OracleResult* other : {&b, &c}) {
    EXPECT_EQ(a.witnessed, other->witnessed);
    EXPECT_EQ(a.witnesses, other->witnesses);
    EXPECT_EQ(a.rays_cast, other->rays_cast);
  }
  SamplingOptions reseeded = two;
  reseeded.seed += 1;
  EXPECT_EQ(oracle.witness(city.camera, reseeded).rays_cast, a.rays_cast);  // same plan, other jitter
}

TEST(RayOracle, ReportsItsDensityAndRates) {
  const RandomCity city = random_city(5);
  const RayOracle oracle(city.scene);
  SamplingOptions o;
  o.spacing_m = 3.0;
  o.frustum_resolution = 128;
  RayLog log;
  const OracleResult r = oracle.witness(city.camera, o, &log);
  EXPECT_EQ(r.density, o);
  EXPECT_EQ(log.rays.size(), r.rays_cast);
  EXPECT_GT(r.rays_per_second(), 0);
  EXPECT_GT(oracle.bare_embree_rays_per_second(log, 1, 0.01), 0);
  const nlohmann::json j = r.density;
  EXPECT_EQ(j.at("spacing_m"), 3.0);
  EXPECT_EQ(j.get<SamplingOptions>(), o);
  const nlohmann::json w = r.witnesses.begin()->second;
  EXPECT_TRUE(w.contains("hit_point"));
}

TEST(RayOracle, RejectsBadOptionsAndCamerasWithTypedErrors) {
  const Scene scene = scene_of({box_building(1, 10, -3, 12, 3, 10)});
  const RayOracle oracle(scene);
  SamplingOptions o;
  o.spacing_m = 0;
  EXPECT_THROW(oracle.witness(kStreetEast, o), InputError);
  Camera c = kStreetEast;
  c.hfov = 4.0;
  EXPECT_THROW(oracle.witness(c), InputError);
}

TEST(RayOracle, EmptySceneWitnessesNothing) {
  const Scene scene;
  const OracleResult r = RayOracle(scene).witness(kStreetEast);
  EXPECT_TRUE(r.witnessed.empty());
  EXPECT_GT(r.rays_cast, 0u);
}

}  // namespace
}  // namespace cullcheck::oracle
