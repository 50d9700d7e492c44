#include "oracle/ray_oracle.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <nlohmann/json.hpp>

#include "core/errors.hpp"
#include "test_scenes.hpp"

namespace cullcheck::oracle {
namespace {

using namespace testing;

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

// A wall mesh across the view at x = 10 (40 m wide, 30 m high, eye at 5 m) hides a box behind
// it at x = 20..22 entirely, except through a 2 m x 2 m window (|y| < 1, 4 < z < 6).
Scene window_scene(bool with_window) {
  const Opening window{19, 21, 4, 6};  // s runs from y = -20
  return scene_of({box_building(2, 20, -3, 22, 3, 10)},
                  {wall_mesh(1, {10, -20, 0}, {0, 1, 0}, 40, 30, with_window ? &window : nullptr)});
}

TEST(RayOracle, BoxBehindAWallMeshIsWitnessedThroughItsWindowAndOnlyThrough) {
  const Camera c = level_camera({0, 0, 5}, 0.0);
  const Scene open = window_scene(true);
  const RayOracle oracle(open);
  const OracleResult r = oracle.witness(c);
  EXPECT_EQ(r.candidates, 2u);
  ASSERT_EQ(r.witnessed, (std::vector<ObjectId>{1, 2}));
  const WitnessRay& w = r.witnesses.at(2);
  // The witness passes the wall's plane inside the window and hits the box.
  const double s = (10 - w.origin.x) / w.direction.x;
  const Vec3 at_wall = w.origin + w.direction * s;
  EXPECT_LT(std::abs(at_wall.y), 1.0) << describe(w);
  EXPECT_GT(at_wall.z, 4.0) << describe(w);
  EXPECT_LT(at_wall.z, 6.0) << describe(w);
  EXPECT_GE(w.hit_point.x, 20.0 - 1e-9);
  const RayOracle::Replay replay = oracle.replay(w, c);
  ASSERT_TRUE(replay.hit.has_value());
  EXPECT_EQ(*replay.hit, 2u);
  EXPECT_TRUE(replay.in_view_volume);

  const Scene closed = window_scene(false);
  EXPECT_EQ(RayOracle(closed).witness(c).witnessed, std::vector<ObjectId>{1});
}

TEST(RayOracle, MeshObjectsAreCandidatesOnlyWhenTheirBoxesMayMeetTheViewVolume) {
  const Scene scene = scene_of({}, {wall_mesh(1, {10, -2, 0}, {0, 1, 0}, 4, 4),      // ahead
                                    wall_mesh(2, {-10, -2, 0}, {0, 1, 0}, 4, 4)});  // behind
  const OracleResult r = RayOracle(scene).witness(level_camera({0, 0, 1.7}, 0.0));
  EXPECT_EQ(r.candidates, 1u);
  EXPECT_EQ(r.witnessed, std::vector<ObjectId>{1});
  EXPECT_EQ(r.witnesses.at(1).aimed_at, 1u);  // the first ray is a surface sample on the wall
  EXPECT_EQ(r.witnesses.at(1).source, RaySource::surface_sample);
}

// Orthographic cameras: parallel rays along the view direction, each from the near plane.
TEST(RayOracle, OrthographicStratifiedGridCoversTheRectangleWithParallelRaysFromTheNearPlane) {
  const Scene empty;
  Camera c = ortho_camera({3, 4, 10}, 0.5, 0.0, 20, 10);
  c.near = 2.0;
  SamplingOptions o;
  o.frustum_resolution = 64;  // 64 columns x 32 rows over 20 m x 10 m
  RayLog log;
  const OracleResult r = RayOracle(empty).witness(c, o, &log);
  EXPECT_EQ(r.rays_cast, 64u * 32u);
  ASSERT_EQ(log.rays.size(), 64u * 32u);
  const CameraBasis b = basis_of(c);
  for (const RayLog::Ray& ray : log.rays) {  // the empty scene's float origin is (0, 0, 0)
    const Vec3 o3{ray.org[0], ray.org[1], ray.org[2]}, d{ray.dir[0], ray.dir[1], ray.dir[2]};
    EXPECT_NEAR(length(d - b.forward), 0.0, 1e-7);
    EXPECT_NEAR(dot(o3 - c.position, b.forward), 2.0, 1e-5);  // on the near plane
    EXPECT_LE(std::abs(dot(o3 - c.position, b.right)), 10.0 + 1e-5);
    EXPECT_LE(std::abs(dot(o3 - c.position, b.up)), 5.0 + 1e-5);
    EXPECT_EQ(ray.t_near, 0.0f);
    EXPECT_NEAR(ray.t_far, 1000.0 - 2.0, 1e-3);  // far - near
  }
}

TEST(RayOracle, OrthographicTopDownSeesRoofsInItsRectangleOnly) {
  // Looking straight down from 50 m over the 40 m x 40 m square |x|, |y| <= 20 (near 1 m): boxes
  // 1 and 3 stand inside it; the 30 m box 2 stands outside (x >= 25), where a perspective camera
  // with a wide enough field of view would see its wall and this one sees nothing.
  const Scene scene = scene_of({box_building(1, -5, -5, 5, 5, 10), box_building(2, 25, -5, 30, 5, 30),
                                box_building(3, 10, 10, 15, 15, 2)});
  Camera c = ortho_camera({0, 0, 50}, 0.0, -kPi / 2, 40, 40);
  c.near = 1.0;
  const RayOracle oracle(scene);
  const OracleResult r = oracle.witness(c);
  EXPECT_EQ(r.candidates, 2u);
  ASSERT_EQ(r.witnessed, (std::vector<ObjectId>{1, 3}));
  for (ObjectId id : r.witnessed) {
    const WitnessRay& w = r.witnesses.at(id);
    const double roof = id == 1 ? 10.0 : 2.0;
    EXPECT_NEAR(w.hit_point.z, roof, 1e-9) << describe(w);  // rays straight down hit roofs
    EXPECT_NEAR(w.origin.z, 49.0, 1e-9) << describe(w);      // from the near plane, 1 m below the eye
    EXPECT_NEAR(w.t_hit, 49.0 - roof, 1e-9) << describe(w);
    EXPECT_NEAR(w.direction.z, -1.0, 1e-15);
    const RayOracle::Replay replay = oracle.replay(w, c);
    ASSERT_TRUE(replay.hit.has_value()) << describe(w);
    EXPECT_EQ(*replay.hit, id);
    EXPECT_TRUE(replay.in_view_volume);
    EXPECT_NEAR(replay.t_hit, w.t_hit, 1e-9);
  }
  EXPECT_EQ(r.witnesses.at(1).source, RaySource::surface_sample);
  EXPECT_EQ(r.witnesses.at(1).aimed_at, 1u);
}

TEST(RayOracle, OrthographicViewHidesWhatAPerspectiveViewShowsOverAWall) {
  // Looking east from (0, 0, 5) through a 10 m x 10 m box: a wall at x = 10 covering |y| <= 6,
  // z <= 12 hides the 40 m tower behind it, which a perspective camera sees above the wall.
  const Scene scene = scene_of({box_building(1, 10, -6, 11, 6, 12), box_building(2, 30, -3, 32, 3, 40)});
  const Camera ortho = ortho_camera({0, 0, 5}, 0.0, 0.0, 10, 10);
  const RayOracle oracle(scene);
  const OracleResult r = oracle.witness(ortho);
  EXPECT_EQ(r.candidates, 2u);
  EXPECT_EQ(r.witnessed, std::vector<ObjectId>{1});
  EXPECT_NEAR(r.witnesses.at(1).hit_point.x, 10.0, 1e-9);
  EXPECT_EQ(oracle.witness(level_camera({0, 0, 5}, 0.0, 60 * kDeg, 90 * kDeg)).witnessed, (std::vector<ObjectId>{1, 2}));
  // Near plane beyond the wall: the wall is clipped and the tower shows.
  Camera past = ortho;
  past.near = 12.0;
  const OracleResult p = oracle.witness(past);
  EXPECT_EQ(p.witnessed, std::vector<ObjectId>{2});
  EXPECT_NEAR(p.witnesses.at(2).hit_point.x, 30.0, 1e-9);
  EXPECT_NEAR(p.witnesses.at(2).origin.x, 12.0, 1e-12);
  EXPECT_NEAR(p.witnesses.at(2).t_hit, 18.0, 1e-9);
}

TEST(RayOracle, OrthographicRunsAreDeterministicAndIndependentOfThreadCount) {
  const RandomCity city = random_city(22);
  Camera c = ortho_camera(city.camera.position + Vec3{0, 0, 60}, 0.3, -0.9, 120, 80);
  SamplingOptions one, two;
  one.threads = 1;
  two.threads = 2;
  const RayOracle oracle(city.scene);
  const OracleResult a = oracle.witness(c, two), b = oracle.witness(c, one);
  EXPECT_EQ(a.witnesses, b.witnesses);
  EXPECT_EQ(a.rays_cast, b.rays_cast);
  ASSERT_GT(a.witnessed.size(), 3u);
  for (const auto& [id, ray] : a.witnesses) {
    const RayOracle::Replay replay = oracle.replay(ray, c);
    ASSERT_TRUE(replay.hit.has_value()) << describe(ray);
    EXPECT_EQ(*replay.hit, id) << describe(ray);
    EXPECT_TRUE(replay.in_view_volume) << describe(ray);
  }
}

TEST(RayOracle, EmptySceneWitnessesNothing) {
  const Scene scene;
  const OracleResult r = RayOracle(scene).witness(kStreetEast);
  EXPECT_TRUE(r.witnessed.empty());
  EXPECT_GT(r.rays_cast, 0u);
}

}  // namespace
}  // namespace cullcheck::oracle
