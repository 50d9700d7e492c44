// CityJSON surfaces into triangles (polygon_triangulation.hpp): a roof with a courtyard hole, a
// concave wall, a face seen edge-on from every axis; the triangles cover the polygon's area once,
// face the way its outer ring turns, and a ring that spans no area gives none.
#include "core/formats/polygon_triangulation.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace cullcheck::formats {
namespace {


// Sum of the triangles' areas, and whether each faces along `normal`.
double area_facing(const std::vector<Vec3>& v, const std::vector<std::array<std::uint32_t, 3>>& triangles, Vec3 normal,
                   bool& all_facing) {
  double area = 0.0;
  all_facing = true;
  for (const auto& t : triangles) {
    const Vec3 n = cross(v[t[1]] - v[t[0]], v[t[2]] - v[t[0]]);
    area += 0.5 * std::sqrt(n.x * n.x + n.y * n.y + n.z * n.z);
    all_facing = all_facing && n.x * normal.x + n.y * normal.y + n.z * normal.z > 0;
  }
  return area;
}

TEST(PolygonTriangulation, ARoofWithACourtyardCoversItsAreaOnce) {
  // A 4 x 4 flat roof at z = 10, counter-clockwise seen from above, with a 2 x 2 hole.
  std::vector<Vec3> v = {{0, 0, 10}, {4, 0, 10}, {4, 4, 10}, {0, 4, 10}, {1, 1, 10}, {1, 3, 10}, {3, 3, 10}, {3, 1, 10}};
  const auto triangles = triangulate_polygon(v, {{0, 1, 2, 3}, {4, 5, 6, 7}});
  bool up = false;
  EXPECT_NEAR(area_facing(v, triangles, {0, 0, 1}, up), 12.0, 1e-9);
  EXPECT_TRUE(up) << "the outer ring turns counter-clockwise seen from above";
  EXPECT_EQ(triangles.size(), 8u);
  EXPECT_EQ(v.size(), 8u) << "no vertex added where no rings cross";
}

TEST(PolygonTriangulation, AConcaveWallFacesItsWay) {
  // An L-shaped wall in the plane y = 5, its ring turning so that it faces -y.
  std::vector<Vec3> v = {{0, 5, 0}, {3, 5, 0}, {3, 5, 1}, {1, 5, 1}, {1, 5, 3}, {0, 5, 3}};
  const auto triangles = triangulate_polygon(v, {{0, 1, 2, 3, 4, 5}});
  bool facing = false;
  EXPECT_NEAR(area_facing(v, triangles, {0, -1, 0}, facing), 5.0, 1e-9);
  EXPECT_TRUE(facing);
  EXPECT_EQ(triangles.size(), 4u);
  // The same wall turned to face +x (in the plane x = 2): the other dropped axis.
  std::vector<Vec3> w;
  for (Vec3 p : v) w.push_back({2, p.x, p.z});
  bool facing_x = false;
  EXPECT_NEAR(area_facing(w, triangulate_polygon(w, {{0, 1, 2, 3, 4, 5}}), {1, 0, 0}, facing_x), 5.0, 1e-9);
  EXPECT_TRUE(facing_x);
}

TEST(PolygonTriangulation, CrossingRingsGetAVertexOnThePlane) {
  // A lopsided bow tie on a sloped roof z = x: its edges cross at (4/3, 4/3), which becomes a vertex.
  std::vector<Vec3> v = {{0, 0, 0}, {4, 4, 4}, {4, 0, 4}, {0, 2, 0}};
  const auto triangles = triangulate_polygon(v, {{0, 1, 2, 3}});
  ASSERT_EQ(v.size(), 5u);
  EXPECT_NEAR(v[4].x, 4.0 / 3, 1e-12);
  EXPECT_NEAR(v[4].y, 4.0 / 3, 1e-12);
  EXPECT_NEAR(v[4].z, 4.0 / 3, 1e-12) << "lifted onto the plane z = x";
  EXPECT_EQ(triangles.size(), 2u);
}

TEST(PolygonTriangulation, ARingWithoutAreaGivesNothing) {
  std::vector<Vec3> v = {{0, 0, 0}, {1, 1, 1}, {2, 2, 2}, {3, 3, 3}};
  EXPECT_TRUE(triangulate_polygon(v, {{0, 1, 2, 3}}).empty());
  EXPECT_TRUE(triangulate_polygon(v, {{0, 1}}).empty());
  EXPECT_TRUE(triangulate_polygon(v, {}).empty());
}

}  // namespace
}  // namespace cullcheck::formats
