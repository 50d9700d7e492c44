// The ray plan's candidate filter (the oracle's own conservative clip-space box test: it must
// never drop an object with a point in the view) and its silhouette-grazing rays.
//
// Replay one random case: ORACLE_FILTER_SEED=<seed> oracle_test --gtest_filter='CandidateFilter.*'
#include "oracle/ray_plan.hpp"

#include <gtest/gtest.h>

#include <cstdlib>
#include <string>

#include "oracle/ray_oracle.hpp"
#include "oracle/surface_samples.hpp"
#include "oracle/view_transform.hpp"
#include "test_scenes.hpp"

namespace cullcheck::oracle {
namespace {

using namespace testing;

bool witnessed(const OracleResult& r, ObjectId id) { return r.witnesses.count(id) == 1; }

TEST(CandidateFilter, KeepsObjectsJustInsideEachEdgeOfTheView) {
  // Eye at 10 m looking east, hfov 60, vfov 40, near 1, far 100. Each object pokes 0.4 m into
  // the view across one edge, 20 m ahead (far: across the far plane); the filter must keep it and
  // the oracle must see it.
  Camera c = level_camera({0, 0, 10}, 0.0, 60 * kDeg, 40 * kDeg);
  c.near = 1.0, c.far = 100.0;
  const double side = 20 * std::tan(30 * kDeg);  // half-width of the view 20 m ahead: 11.547 m
  const double up = 20 * std::tan(20 * kDeg);    // half-height there: 7.279 m
  const std::vector<Building> buildings = {
      box_building(1, 19.5, -side - 0.1 - 0.5, 20.5, -side - 0.1 + 0.5, 12),  // right edge (world -y)
      box_building(2, 19.5, side + 0.1 - 0.5, 20.5, side + 0.1 + 0.5, 12),    // left edge
      box_building(3, 19.5, -0.5, 20.5, 0.5, 10 - up + 0.4),                  // up across the bottom edge
      box_building(4, 99.4, -0.5, 100.4, 0.5, 12),                            // across the far plane
  };
  // Down across the top edge: a floating 1 x 1 m sheet facing the eye.
  const MeshObject top = wall_mesh(5, {20, -0.5, 10 + up - 0.4}, {0, 1, 0}, 1, 1);
  const Scene scene = scene_of(buildings, {top});
  const ViewTransform view(c);
  for (const Building& b : buildings) EXPECT_TRUE(view.may_meet(b.bounds)) << "building " << b.id;
  EXPECT_TRUE(view.may_meet(top.bounds));
  const OracleResult r = RayOracle(scene).witness(c);
  EXPECT_EQ(r.candidates, 5u);
  for (ObjectId id : {1u, 2u, 3u, 4u, 5u}) EXPECT_TRUE(witnessed(r, id)) << "object " << id;
  // And objects just outside each edge are dropped (the view is 20.5 tan 30 = 11.836 m wide at
  // the boxes' far faces).
  EXPECT_FALSE(view.may_meet(box_building(6, 19.5, -side - 1.6, 20.5, -side - 0.6, 12).bounds));
  EXPECT_FALSE(view.may_meet(box_building(7, 19.5, side + 0.6, 20.5, side + 1.6, 12).bounds));
  EXPECT_FALSE(view.may_meet(box_building(8, 100.1, -0.5, 101.1, 0.5, 12).bounds));  // beyond far
  EXPECT_FALSE(view.may_meet(box_building(9, 0.1, -0.1, 0.2, 0.1, 12).bounds));      // before near
  EXPECT_FALSE(view.may_meet(box_building(10, 19.5, -0.5, 20.5, 0.5, 10 - up - 0.6).bounds));  // below the bottom
}

TEST(CandidateFilter, KeepsAnObjectMostlyBehindTheEyeWithAWideFieldOfView) {
  // hfov 170 degrees: the side planes are 85 degrees from the view direction, so a long block
  // reaching from 20 m behind the eye to 0.5 m ahead of it, 5 m to the side, shows its front end
  // (at 84.3 degrees); a block ending 1 m behind the eye (at 101 degrees) does not.
  const Camera c = level_camera({0, 0, 1.7}, 0.0, 170 * kDeg, 60 * kDeg);
  const Building front = box_building(1, -20, 5, 0.5, 8, 10);
  const Building behind = box_building(2, -20, -8, -1, -5, 10);
  const ViewTransform view(c);
  EXPECT_TRUE(view.may_meet(front.bounds));
  EXPECT_FALSE(view.may_meet(behind.bounds));
  const OracleResult r = RayOracle(scene_of({front, behind})).witness(c);
  EXPECT_TRUE(witnessed(r, 1));
  EXPECT_FALSE(witnessed(r, 2));
  EXPECT_EQ(r.candidates, 1u);
}

// Random cameras (perspective up to nearly 180 degrees, orthographic, omnidirectional) and
// random boxes around them: whenever a point of a box is in the view, the box is kept.
void check_filter(std::uint64_t seed, std::size_t& kept, std::size_t& dropped) {
  SplitMix64 rng(seed * 0x9E3779B97F4A7C15ULL + 7);
  auto uniform = [&](double lo, double hi) { return lo + (hi - lo) * rng.unit(); };
  Camera c;
  c.position = {uniform(-100, 100), uniform(-100, 100), uniform(0, 50)};
  c.yaw = uniform(0, kTwoPi), c.pitch = uniform(-kPi / 2, kPi / 2), c.roll = uniform(-kPi, kPi);
  c.near = uniform(0, 3), c.far = c.near + uniform(5, 80);
  const int kind = int(rng.next() % 5);
  if (kind == 0) {
    c.projection = Projection::orthographic;
    c.ortho_width = uniform(1, 60), c.ortho_height = uniform(1, 60);
  } else if (kind == 1) {
    c.hfov = kTwoPi;
  } else {
    c.hfov = uniform(0.05, kPi - 1e-3), c.vfov = uniform(0.05, kPi - 1e-3);
  }
  const ViewTransform view(c);
  const std::string replay = "replay: ORACLE_FILTER_SEED=" + std::to_string(seed) + " oracle_test --gtest_filter='CandidateFilter.*'";
  for (int b = 0; b < 40; ++b) {
    const Vec3 centre = c.position + Vec3{uniform(-60, 60), uniform(-60, 60), uniform(-30, 30)};
    const Vec3 half{uniform(0.01, 8), uniform(0.01, 8), uniform(0.01, 8)};
    const Box3 box{centre - half, centre + half};
    const bool may = view.may_meet(box);
    (may ? kept : dropped) += 1;
    if (may) continue;
    for (int s = 0; s < 200; ++s) {
      const Vec3 p{box.lo.x + (box.hi.x - box.lo.x) * rng.unit(), box.lo.y + (box.hi.y - box.lo.y) * rng.unit(),
                   box.lo.z + (box.hi.z - box.lo.z) * rng.unit()};
      ASSERT_FALSE(view.contains(p)) << "the filter dropped a box holding a point in the view: (" << p.x << ", " << p.y << ", "
                                     << p.z << ")\n" << replay;
    }
  }
}

TEST(CandidateFilter, NeverDropsABoxHoldingAPointInTheView) {
  std::size_t kept = 0, dropped = 0;
  if (const char* seed = std::getenv("ORACLE_FILTER_SEED")) {
    check_filter(std::strtoull(seed, nullptr, 10), kept, dropped);
    return;
  }
  for (std::uint64_t seed = 1; seed <= 300; ++seed) {
    check_filter(seed, kept, dropped);
    if (HasFatalFailure()) return;
  }
  // Not vacuous: both outcomes occur.
  EXPECT_GT(kept, 1000u);
  EXPECT_GT(dropped, 1000u);
}

TEST(GrazingRays, RunBesideEverySilhouetteEdgeOnBothSidesAndAreCounted) {
  // A 2 x 6 x 10 m block 10 m east of the eye. Seen from (0, 0, 1.7): the west wall faces the
  // eye, the other walls and the roof face away, so the silhouette is the west wall's two
  // vertical edges (10 m: max(4, 10 / 2) = 5 intervals, 6 points) and its roof edge (6 m:
  // max(4, 3) = 4 intervals, 5 points): 2 rays per point, 34 rays.
  const Camera c = level_camera({0, 0, 1.7}, 0.0, 100 * kDeg, 100 * kDeg);
  const Scene scene = scene_of({box_building(1, 10, -3, 12, 3, 10)});
  SamplingOptions o;
  const OracleResult r = RayOracle(scene).witness(c, o);
  EXPECT_EQ(r.grazing_rays, 34u);
  o.graze_offset = 0.0;
  const OracleResult none = RayOracle(scene).witness(c, o);
  EXPECT_EQ(none.grazing_rays, 0u);
  EXPECT_EQ(r.rays_cast, none.rays_cast + 34u);
  // From above the roof (eye at 30 m), the roof faces the eye: the silhouette is now the west
  // wall's vertical edges and the three roof edges of the walls facing away.
  const Camera above = level_camera({0, 0, 30}, 0.0, 100 * kDeg, 170 * kDeg);
  EXPECT_EQ(RayOracle(scene).witness(above, SamplingOptions{}).grazing_rays,
            2u * (6 + 6 + 5 + 5 + 5));  // vertical 6 + 6; roof edges south 2 m: 4 intervals, east 6 m: 4, north: 4
}

// The block x0..x1, y0..y1, 0..h as a closed mesh of 12 triangles; `shared` false gives every
// triangle its own three vertices, as many glTF files store them.
MeshObject box_mesh_object(ObjectId id, double x0, double y0, double x1, double y1, double h, bool shared = true) {
  const std::vector<Vec3> corners = {{x0, y0, 0}, {x1, y0, 0}, {x1, y1, 0}, {x0, y1, 0},
                                     {x0, y0, h}, {x1, y0, h}, {x1, y1, h}, {x0, y1, h}};
  const std::vector<std::array<std::uint32_t, 3>> faces = {{0, 2, 1}, {0, 3, 2}, {4, 5, 6}, {4, 6, 7}, {0, 1, 5}, {0, 5, 4},
                                                           {1, 2, 6}, {1, 6, 5}, {2, 3, 7}, {2, 7, 6}, {3, 0, 4}, {3, 4, 7}};
  if (shared) return mesh_object(id, corners, faces);
  std::vector<Vec3> v;
  std::vector<std::array<std::uint32_t, 3>> t;
  for (const auto& f : faces) {
    const auto base = static_cast<std::uint32_t>(v.size());
    for (std::uint32_t i : f) v.push_back(corners[i]);
    t.push_back({base, base + 1, base + 2});
  }
  return mesh_object(id, std::move(v), std::move(t));
}

TEST(GrazingRays, RunBesideAMeshObjectsSilhouetteEdgesWhetherOrNotItsTrianglesShareVertices) {
  // The block of the test above as a closed mesh. From (0, 0, 1.7) only its west face (x = 10)
  // faces the eye, the bottom face included in those facing away: the silhouette is the west
  // face's four edges, vertical 10 m (6 points each) and horizontal 6 m at z = 0 and z = 10
  // (5 points each); the diagonals inside faces are not on it. 2 rays per point: 44.
  const Camera c = level_camera({0, 0, 1.7}, 0.0, 100 * kDeg, 100 * kDeg);
  for (bool shared : {true, false}) {
    const Scene scene = scene_of({}, {box_mesh_object(1, 10, -3, 12, 3, 10, shared)});
    const OracleResult r = RayOracle(scene).witness(c, SamplingOptions{});
    EXPECT_EQ(r.grazing_rays, 44u) << (shared ? "shared" : "unshared") << " vertices";
    SamplingOptions off;
    off.graze_offset = 0.0;
    EXPECT_EQ(r.rays_cast, RayOracle(scene).witness(c, off).rays_cast + 44u);
  }
  // An open sheet (one wall quad, two triangles) has its four boundary edges on the silhouette
  // from either side: 10 m wide (5 intervals, 6 points), 5 m tall (max(4, 3) = 4 intervals,
  // 5 points), facing the eye at x = 10: 2 * (6 + 6 + 5 + 5) rays.
  const Scene sheet = scene_of({}, {wall_mesh(2, {10, -5, 0}, {0, 1, 0}, 10, 5)});
  EXPECT_EQ(RayOracle(sheet).witness(c, SamplingOptions{}).grazing_rays, 2u * (6 + 6 + 5 + 5));
}

// Two tall blocks A and B leave a gap about 3e-5 rad wide between A's north-west edge (10, 0)
// and B's south-east edge (12, 0.20036), seen from (0, -1): slopes 0.1 and 0.10003. Through it
// lies the wall C at x = 30, which nothing else shows. Few stratified rays and C's samples away
// from the gap, so only a grazing ray finds it: along a building's silhouette edge, or a mesh
// occluder's (`meshes`; B's triangles share no vertex).
void expect_sliver_witnessed_only_by_grazing(bool meshes) {
  SCOPED_TRACE(meshes ? "mesh objects" : "buildings");
  const Camera c = level_camera({0, -1, 1.7}, 0.0, 60 * kDeg, 60 * kDeg);
  const Scene scene =
      meshes ? scene_of({}, {box_mesh_object(1, 10, -20, 12, 0, 20), box_mesh_object(2, 10, 0.20036, 12, 20, 20, false),
                             box_mesh_object(3, 30, -9.3, 31, 10.7, 12)})
             : scene_of({box_building(1, 10, -20, 12, 0, 20), box_building(2, 10, 0.20036, 12, 20, 20),
                         box_building(3, 30, -9.3, 31, 10.7, 12)});
  SamplingOptions o;
  o.frustum_resolution = 16;
  o.graze_offset = 0.0;
  EXPECT_EQ(RayOracle(scene).witness(c, o).witnessed, (std::vector<ObjectId>{1, 2}));
  o.graze_offset = 1e-5;
  const OracleResult with = RayOracle(scene).witness(c, o);
  EXPECT_EQ(with.witnessed, (std::vector<ObjectId>{1, 2, 3}));
  ASSERT_TRUE(witnessed(with, 3));
  EXPECT_EQ(with.witnesses.at(3).source, RaySource::grazing);
  EXPECT_NEAR(with.witnesses.at(3).hit_point.x, 30.0, 1e-6);
}

TEST(GrazingRays, WitnessABuildingSeenOnlyThroughASliverBetweenTwoOccluders) { expect_sliver_witnessed_only_by_grazing(false); }

TEST(GrazingRays, WitnessAMeshObjectSeenOnlyThroughASliverBetweenTwoMeshOccluders) {
  expect_sliver_witnessed_only_by_grazing(true);
}

// The ray toward each point, whether planned one point at a time (ray_toward) or as a run
// (rays_toward, with the box the points lie in, so that tests the box settles are skipped).
bool same_rays(const std::vector<PlannedRay>& a, const std::vector<PlannedRay>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t k = 0; k < a.size(); ++k)
    if (!(a[k].origin == b[k].origin && a[k].direction == b[k].direction && a[k].t_near == b[k].t_near &&
          a[k].t_far == b[k].t_far && a[k].target == b[k].target && a[k].aimed_at == b[k].aimed_at && a[k].source == b[k].source))
      return false;
  return true;
}

TEST(RunPlanning, ABoxSettlesTheSidesAndTheFarEndOnlyWithAMarginToSpare) {
  // Eye at 10 m looking east, hfov 60, vfov 40, near 1, far 100: 20 m ahead the view is 11.547 m
  // to either side.
  Camera c = level_camera({0, 0, 10}, 0.0, 60 * kDeg, 40 * kDeg);
  c.near = 1.0, c.far = 100.0;
  const ViewCone cone(c);
  auto box = [](double x0, double y0, double x1, double y1, double z0, double z1) { return Box3{{x0, y0, z0}, {x1, y1, z1}}; };
  const auto inside = cone.settles(box(19, -2, 21, 2, 8, 12));
  EXPECT_TRUE(inside.sides);
  EXPECT_TRUE(inside.before_far);
  EXPECT_FALSE(cone.settles(box(19, 10, 21, 12, 8, 12)).sides);          // across the left plane
  EXPECT_FALSE(cone.settles(box(19, -2, 21, 2, 8, 18)).sides);           // across the top plane
  EXPECT_FALSE(cone.settles(box(19, -2, 21, 2, 2, 12)).sides);           // across the bottom plane
  const auto deep = cone.settles(box(98, -2, 99.9995, 2, 8, 12));       // ends 0.5 mm before the far plane
  EXPECT_TRUE(deep.sides);
  EXPECT_FALSE(deep.before_far);  // the ray's 1e-5 relative overshoot reaches past far
  EXPECT_TRUE(cone.settles(box(98, -2, 99.99, 2, 8, 12)).before_far);   // 1 cm before it: room enough
  EXPECT_FALSE(cone.settles(box(-1, -1, 1, 1, 9, 11)).sides);            // around the eye
  Camera omni = c;
  omni.hfov = kTwoPi;
  EXPECT_FALSE(ViewCone(omni).settles(box(19, -2, 21, 2, 8, 12)).sides);  // no planes to settle
}

// rays_toward gives ray_toward's rays bit for bit, with and without the box settling tests, on
// every candidate of random cities (perspective, omnidirectional and orthographic views), for
// surface rays (ending at their points) and rays run on to the far plane. The settled paths were
// taken (counted).
TEST(RunPlanning, RunsGiveTheRaysOfOnePointAtATimeBitForBit) {
  std::size_t objects = 0, sides_settled = 0, far_settled = 0, rays = 0;
  for (std::uint64_t seed = 1; seed <= 40; ++seed) {
    const RandomCity city = random_city(seed);
    const RayOracle oracle(city.scene);
    const RayPlan plan(city.scene, oracle.mesh(), city.camera, SamplingOptions{});
    const ViewCone& cone = plan.cone();
    for (std::size_t i = 0; i < city.scene.buildings.size(); ++i) {
      const Building& b = city.scene.buildings[i];
      if (!cone.transform().may_meet(b.bounds)) continue;
      ++objects;
      const std::vector<Vec3> points = surface_samples(b, oracle.mesh().roofs[i], SamplingOptions{}).points;
      const ViewCone::BoxSettles settled = cone.settles(b.bounds);
      sides_settled += settled.sides ? 1 : 0;
      far_settled += settled.before_far ? 1 : 0;
      for (bool to_far : {false, true}) {
        PlannedRay prototype{};
        prototype.aimed_at = std::uint32_t(i);
        std::vector<PlannedRay> one, run, run_in_box;
        PlannedRay ray = prototype;
        for (Vec3 p : points)
          if (cone.ray_toward(p, ray, to_far)) one.push_back(ray);
        cone.rays_toward(points, prototype, run, nullptr, to_far);
        cone.rays_toward(points, prototype, run_in_box, &b.bounds, to_far);
        SCOPED_TRACE("random_city(" + std::to_string(seed) + "), " + city.kind + ", building " + std::to_string(b.id) +
                     (to_far ? ", to the far plane" : ", to the point"));
        EXPECT_TRUE(same_rays(one, run));
        EXPECT_TRUE(same_rays(one, run_in_box));
        rays += one.size();
      }
    }
  }
  // Pinned: the cities' candidates, how many boxes settled each test, the rays compared.
  EXPECT_EQ(objects, 1449u);
  EXPECT_EQ(sides_settled, 117u);
  EXPECT_EQ(far_settled, 117u);
  EXPECT_EQ(rays, 2441684u);
}

}  // namespace
}  // namespace cullcheck::oracle
