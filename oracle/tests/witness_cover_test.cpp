// Which triangles draw the point a witness ray saw: a ray grazing the edge between a face turned
// to the eye and one turned away may be credited to either; the point is drawn when the facing one
// is kept, and only then.
#include "oracle/witness_cover.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <vector>

namespace cullcheck::oracle {
namespace {

TEST(WitnessCover, PointTriangleDistanceIsThatOfTheClosestPoint) {
  const Vec3 a{0, 0, 0}, b{1, 0, 0}, c{0, 1, 0};
  EXPECT_DOUBLE_EQ(point_triangle_distance({0.25, 0.25, 2}, a, b, c), 2.0);  // above the inside
  EXPECT_DOUBLE_EQ(point_triangle_distance({2, 0, 0}, a, b, c), 1.0);        // beyond vertex b
  EXPECT_DOUBLE_EQ(point_triangle_distance({-1, -1, 0}, a, b, c), std::sqrt(2.0));
  EXPECT_DOUBLE_EQ(point_triangle_distance({1, 1, 0}, a, b, c), std::sqrt(0.5));  // beyond edge bc
  EXPECT_DOUBLE_EQ(point_triangle_distance({0.5, -3, 4}, a, b, c), 5.0);          // beyond edge ab
}

// The unit cube [0, 1]^3 as one object, faces wound outward: triangles 0-1 the face x = 0,
// 2-3 the face y = 0, then the other four faces.
TriangleMesh cube() {
  TriangleMesh m;
  m.vertices = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  m.triangles = {{0, 4, 7}, {0, 7, 3},   // x = 0, normal -x
                 {0, 1, 5}, {0, 5, 4},   // y = 0, normal -y
                 {1, 2, 6}, {1, 6, 5},   // x = 1
                 {3, 7, 6}, {3, 6, 2},   // y = 1
                 {0, 3, 2}, {0, 2, 1},   // z = 0
                 {4, 5, 6}, {4, 6, 7}};  // z = 1
  m.owner_index.assign(12, 0);
  m.owner_id.assign(12, 1);
  m.object_ids = {1};
  m.first_triangle = {0};
  return m;
}

WitnessRay ray_to(Vec3 eye, Vec3 point, std::uint32_t credited) {
  WitnessRay r;
  r.origin = eye;
  const Vec3 d = point - eye;
  r.direction = d * (1.0 / length(d));
  r.t_hit = length(d);
  r.hit_point = point;
  r.target = point;
  r.triangle = credited;
  return r;
}

TEST(WitnessCover, AGrazedEdgeIsDrawnByTheKeptFaceTurnedToTheEye) {
  const TriangleMesh m = cube();
  const Vec3 eye{-5, 3, 0.5};  // sees the face x = 0; the face y = 0 turns away from it
  for (const Vec3 n : {Vec3{-1, 0, 0}, Vec3{0, -1, 0}}) {
    const auto& t = m.triangles[n.x < 0 ? 0 : 2];
    const Vec3 normal = cross(m.vertices[t[1]] - m.vertices[t[0]], m.vertices[t[2]] - m.vertices[t[0]]);
    ASSERT_GT(dot(normal, n), 0) << "the cube is wound outward";
  }
  const WitnessRay edge = ray_to(eye, {0, 0, 0.5}, 2);  // the edge x = y = 0, credited to y = 0
  auto kept = [](std::set<std::uint32_t> s) { return [s](std::uint32_t t) { return s.count(t) > 0; }; };
  EXPECT_TRUE(seen_point_drawn(m, 0, edge, kept({0, 1, 4, 5, 6, 7, 8, 9, 10, 11})))
      << "the face x = 0 is kept and contains the grazed edge";
  EXPECT_FALSE(seen_point_drawn(m, 0, edge, kept({4, 5, 6, 7, 8, 9, 10, 11})))
      << "neither face at the edge is kept";
  EXPECT_FALSE(seen_point_drawn(m, 0, edge, kept({2, 3}))) << "the face kept turns its back to the ray";
  // A point inside the turned-away face, 0.5 m from any kept face: not drawn.
  const WitnessRay inside = ray_to(eye, {0.5, 0, 0.5}, 2);
  EXPECT_FALSE(seen_point_drawn(m, 0, inside, kept({0, 1, 4, 5, 6, 7, 8, 9, 10, 11})));
  // The tolerance: a hit 0.5 mm off the edge counts, 5 mm does not.
  EXPECT_TRUE(seen_point_drawn(m, 0, ray_to(eye, {0.0005, 0, 0.5}, 2), kept({0, 1})));
  EXPECT_FALSE(seen_point_drawn(m, 0, ray_to(eye, {0.005, 0, 0.5}, 2), kept({0, 1})));
  EXPECT_FALSE(seen_point_drawn(m, 1, edge, kept({0, 1}))) << "no object 1";
}

// The verdict the report and the slice-wise property share: culled, drawn, drawn by the kept face
// beside a dropped one, or missed.
TEST(WitnessCover, AWitnessIsDrawnDrawnByAnotherOrMissed) {
  TriangleMesh m = cube();
  const Vec3 eye{-5, 3, 0.5};
  const WitnessRay edge = ray_to(eye, {0, 0, 0.5}, 2), inside = ray_to(eye, {0.5, 0, 0.5}, 2), front = ray_to(eye, {0, 0.5, 0.5}, 0);
  std::vector<char> all_but_y0(12, 1);
  all_but_y0[2] = all_but_y0[3] = 0;
  EXPECT_EQ(witness_verdict(m, 2, edge, nullptr), WitnessVerdict::missed) << "the object culled";
  EXPECT_EQ(witness_verdict(m, 0, front, &all_but_y0), WitnessVerdict::drawn);
  EXPECT_EQ(witness_verdict(m, 2, edge, &all_but_y0), WitnessVerdict::drawn_by_another);
  EXPECT_EQ(witness_verdict(m, 2, inside, &all_but_y0), WitnessVerdict::missed);
  const std::vector<char> none(12, 0);
  EXPECT_EQ(witness_verdict(m, 0, front, &none), WitnessVerdict::missed);
  m.building_count = 1;  // a 2.5D building is drawn whole once kept
  EXPECT_EQ(witness_verdict(m, 0, front, &none), WitnessVerdict::drawn);
}

}  // namespace
}  // namespace cullcheck::oracle
