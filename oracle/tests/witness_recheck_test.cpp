// The double-precision re-check of witness rays: a witness that a nearer occluder blocks in
// double precision (as a float-rounding sliver would let through) is dropped; one that really
// reaches its object stands; both are counted in the oracle's answer.
#include "oracle/witness_recheck.hpp"

#include <gtest/gtest.h>

#include <stdexcept>

#include "oracle/oracle.hpp"
#include "test_scenes.hpp"

namespace cullcheck::oracle {
namespace {

using namespace testing;

// A (id 1) is a wall-like block 10 m east whose north-west vertical edge is at (10, 0); C (id 3)
// is a wide wall 30 m east, partly hidden behind A.
const Scene& scene() {
  static const Scene s = scene_of({box_building(1, 10, -20, 12, 0, 20), box_building(3, 30, -15, 31, 15, 12)});
  return s;
}
const Camera kEye = level_camera({0, -1, 1.7}, 0.0, 60 * kDeg, 60 * kDeg);

// The ray from the eye through the point (10, y, 4) on A's west face plane, run to the far
// plane: it claims to witness C.
WitnessRay ray_past_a(double y) {
  WitnessRay r;
  r.source = RaySource::grazing;
  r.origin = kEye.position;
  r.direction = normalized(Vec3{10, y, 4} - kEye.position);
  r.t_near = kEye.near / r.direction.x;
  r.t_far = kEye.far / r.direction.x;
  r.target = {10, y, 4};
  r.aimed_at = 1;
  return r;
}

TEST(WitnessRecheck, DropsAWitnessThatANearerOccluderBlocksInDoublePrecision) {
  const Oracle oracle(scene());
  // 1e-9 m inside A's edge: far below float resolution at 10 m (about 1e-6), the kind of ray a
  // single-precision cast can let slip past A. In double it hits A first.
  const WitnessRay sliver = ray_past_a(-1e-9);
  const WitnessRecheck r = oracle.exact_triangles().recheck(sliver, 3, kEye);
  EXPECT_EQ(r.verdict, RecheckVerdict::blocked);
  ASSERT_TRUE(r.first_hit.has_value());
  EXPECT_EQ(*r.first_hit, 1u);
  EXPECT_NEAR(r.t_hit, length(Vec3{10, -1e-9, 4} - kEye.position), 1e-9);
  EXPECT_FALSE(r.stands());
}

TEST(WitnessRecheck, AWitnessThatReallyReachesItsObjectStands) {
  const Oracle oracle(scene());
  const WitnessRay past = ray_past_a(+1e-9);  // 1e-9 m outside the edge: on to C at x = 30
  const WitnessRecheck r = oracle.exact_triangles().recheck(past, 3, kEye);
  EXPECT_EQ(r.verdict, RecheckVerdict::stands);
  ASSERT_TRUE(r.first_hit.has_value());
  EXPECT_EQ(*r.first_hit, 3u);
  EXPECT_NEAR(r.t_hit, 30.0 / past.direction.x, 1e-9);
}

TEST(WitnessRecheck, DropsAWitnessThatReachesNothingOrHitsOutsideTheView) {
  const Oracle oracle(scene());
  WitnessRay up = ray_past_a(5);
  up.direction = normalized(Vec3{10, 5, 40} - kEye.position);  // over everything
  EXPECT_EQ(oracle.exact_triangles().recheck(up, 3, kEye).verdict, RecheckVerdict::reaches_nothing);
  // The same ray as the standing one, judged for a camera whose far plane is before C.
  Camera short_sight = kEye;
  short_sight.far = 20.0;
  WitnessRay past = ray_past_a(+1e-9);
  EXPECT_EQ(oracle.exact_triangles().recheck(past, 3, short_sight).verdict, RecheckVerdict::outside_view);
}

TEST(WitnessRecheck, OracleAnswerCountsEachWitnessOnce) {
  const Oracle oracle(scene());
  OracleAnswer answer;  // a synthetic answer: the oracle claims C through the sliver ray
  answer.model = kModelRaySampling3d;
  const WitnessRay sliver = ray_past_a(-1e-9);
  EXPECT_FALSE(oracle.recheck_witness(answer, 3, sliver, kEye).stands());
  EXPECT_EQ(answer.witness_recheck, (WitnessRecheckCounts{1, 1}));
  EXPECT_FALSE(oracle.recheck_witness(answer, 3, sliver, kEye).stands());  // kept, not re-cast
  EXPECT_EQ(answer.witness_recheck, (WitnessRecheckCounts{1, 1}));
  WitnessRay pixel = ray_past_a(+1e-9);
  pixel.source = RaySource::pixel;
  EXPECT_TRUE(oracle.recheck_witness(answer, 3, pixel, kEye).stands());
  EXPECT_EQ(answer.witness_recheck, (WitnessRecheckCounts{2, 1}));
}

TEST(WitnessRecheck, AFurtherWitnessThatStandsReplacesADroppedFirstOne) {
  const Oracle oracle(scene());
  OracleAnswer answer;
  answer.model = kModelRaySampling3d;
  answer.visible = {3};
  answer.sampling.emplace();
  answer.sampling->witnessed = {3};
  answer.sampling->witnesses[3] = ray_past_a(-1e-9);  // blocked by A in double precision
  answer.sampling->further_witnesses[3] = {ray_past_a(-2e-9), ray_past_a(+1e-9)};
  EXPECT_TRUE(oracle.confirm_witness(answer, 3, kEye).stands());
  EXPECT_EQ(answer.sampling->witnesses.at(3), ray_past_a(+1e-9));
  EXPECT_EQ(answer.witness_recheck, (WitnessRecheckCounts{1, 0}));

  OracleAnswer blocked = answer;
  blocked.rechecked.clear();
  blocked.witness_recheck = {};
  blocked.sampling->witnesses[3] = ray_past_a(-1e-9);
  blocked.sampling->further_witnesses[3] = {ray_past_a(-2e-9)};
  EXPECT_FALSE(oracle.confirm_witness(blocked, 3, kEye).stands());
  EXPECT_EQ(blocked.witness_recheck, (WitnessRecheckCounts{1, 1}));
  EXPECT_THROW(oracle.confirm_witness(blocked, 1, kEye), std::logic_error);  // no witness of A in it
}

TEST(WitnessRecheck, EveryWitnessOfARealQueryStands) {
  // The oracle's own witnesses (surface samples, grazing rays, the stratified grid) pass the
  // re-check on an ordinary scene: the re-check agrees with Embree away from rounding slivers.
  const Oracle oracle(scene());
  OracleOptions o;
  o.allow_exact_2d = false;
  OracleAnswer answer = oracle.visible_set(kEye, o);
  ASSERT_TRUE(answer.sampling.has_value());
  EXPECT_EQ(answer.visible, (std::vector<ObjectId>{1, 3}));
  for (const ObjectId id : answer.visible) EXPECT_TRUE(oracle.confirm_witness(answer, id, kEye).stands()) << id;
  EXPECT_EQ(answer.witness_recheck, (WitnessRecheckCounts{2, 0}));
}

TEST(DoublePrecisionScene, RaysThroughASharedEdgeOrVertexStillHit) {
  // Watertight: a ray through the diagonal two wall triangles share, or the one two roof
  // triangles share, cannot slip between them.
  const Scene s = scene_of({box_building(1, 10, -3, 12, 3, 10)});
  const Oracle oracle(s);
  const DoublePrecisionScene& tris = oracle.exact_triangles();
  // The west wall (x = 10) is split along its diagonal (10, -3, 0) - (10, 3, 10); its midpoint is (10, 0, 5).
  const Vec3 eye{0, 0, 5};
  const auto mid = tris.first_hit(eye, {1, 0, 0}, 0, 100);
  ASSERT_TRUE(mid.has_value());
  EXPECT_NEAR(mid->t, 10.0, 1e-12);
  // The roof's two triangles share a diagonal through its centre (11, 0, 10), whichever diagonal.
  const auto roof = tris.first_hit({11, 0, 30}, {0, 0, -1}, 0, 100);
  ASSERT_TRUE(roof.has_value());
  EXPECT_NEAR(roof->t, 20.0, 1e-12);
}

}  // namespace
}  // namespace cullcheck::oracle
