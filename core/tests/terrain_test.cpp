// The terrain's grid (core/terrain.hpp): triangle numbering and winding, heights between the
// vertices, holes, bounds, and validation naming the field.
#include <gtest/gtest.h>

#include <cmath>

#include "core/errors.hpp"
#include "core/terrain.hpp"

namespace cullcheck {
namespace {

// 4 x 3 vertices 10 m east, 5 m north apart from (100, 200), z = 2x - y + 3 (a plane).
Terrain plane() {
  Terrain t;
  t.corner = {100, 200};
  t.dx = 10, t.dy = 5;
  t.nx = 4, t.ny = 3;
  for (std::uint32_t j = 0; j < t.ny; ++j)
    for (std::uint32_t i = 0; i < t.nx; ++i) t.z.push_back(2 * (100 + 10.0 * i) - (200 + 5.0 * j) + 3);
  return t;
}

TEST(Terrain, TwoCounterClockwiseTrianglesACellSplitSouthWestToNorthEast) {
  const Terrain t = plane();
  EXPECT_EQ(t.cell_count(), 6u);
  EXPECT_EQ(t.triangle_count(), 12u);
  EXPECT_EQ(t.triangle_vertices(0), (std::array<std::size_t, 3>{0, 1, 5}));
  EXPECT_EQ(t.triangle_vertices(1), (std::array<std::size_t, 3>{0, 5, 4}));
  EXPECT_EQ(t.triangle_vertices(7), (std::array<std::size_t, 3>{4, 9, 8}));  // cell (0, 1), north-west half
  double area = 0;
  for (std::size_t k = 0; k < t.triangle_count(); ++k) {
    const auto v = t.triangle(k);
    const double twice = cross(plan(v[1]) - plan(v[0]), plan(v[2]) - plan(v[0]));
    EXPECT_GT(twice, 0.0) << "triangle " << k;
    area += twice / 2;
  }
  EXPECT_DOUBLE_EQ(area, 30.0 * 10.0);
  EXPECT_EQ(t.triangle(0)[1], (Vec3{110, 200, 23}));
}

TEST(Terrain, HeightsBetweenVerticesLieOnTheirTriangle) {
  const Terrain t = plane();
  for (const Vec2 p : {Vec2{100, 200}, Vec2{130, 210}, Vec2{104.5, 201.25}, Vec2{117, 208.9}, Vec2{125, 202.5}})
    EXPECT_NEAR(t.height_at(p), 2 * p.x - p.y + 3, 1e-9) << p.x << ", " << p.y;
  EXPECT_TRUE(std::isnan(t.height_at({99.9, 201})));
  EXPECT_TRUE(std::isnan(t.height_at({110, 210.1})));
  // Off a plane the two halves of a cell differ: the diagonal decides.
  Terrain bump = plane();
  bump.z[t.index(1, 0)] += 10;  // raises the south-east half of cell (0, 0) only
  EXPECT_NEAR(bump.height_at({107, 201}), 2 * 107.0 - 201 + 3 + 10 * (0.7 - 0.2), 1e-9);
  EXPECT_NEAR(bump.height_at({101, 204}), 2 * 101.0 - 204 + 3, 1e-9);
  const Box3 b = t.bounds();
  EXPECT_EQ(b.lo, (Vec3{100, 200, 2 * 100.0 - 210 + 3}));
  EXPECT_EQ(b.hi, (Vec3{130, 210, 2 * 130.0 - 200 + 3}));
}

TEST(Terrain, AHoleRemovesTheTrianglesTouchingIt) {
  Terrain t = plane();
  t.hole.assign(t.vertex_count(), 0);
  t.hole[t.index(1, 1)] = 1;
  t.z[t.index(1, 1)] = NAN;  // a hole's height is never read
  EXPECT_NO_THROW(validate(t));
  EXPECT_EQ(t.present_triangle_count(), 6u);
  EXPECT_TRUE(std::isnan(t.height_at({111, 204})));
  EXPECT_FALSE(std::isnan(t.height_at({125, 202})));
  EXPECT_FALSE(std::isnan(t.bounds().hi.z));
}

TEST(Terrain, ValidationNamesTheField) {
  const auto field_of = [](const Terrain& t) {
    try {
      validate(t, "dem");
    } catch (const InputError& e) {
      return e.field();
    }
    return std::string();
  };
  Terrain t = plane();
  EXPECT_EQ(field_of(t), "");
  t.nx = 1;
  EXPECT_EQ(field_of(t), "size");
  t = plane();
  t.dx = 0;
  EXPECT_EQ(field_of(t), "spacing");
  t = plane();
  t.z.pop_back();
  EXPECT_EQ(field_of(t), "heights");
  t = plane();
  t.z[3] = INFINITY;
  EXPECT_EQ(field_of(t), "heights");
  t = plane();
  t.hole.assign(3, 0);
  EXPECT_EQ(field_of(t), "holes");
  t.hole.assign(t.vertex_count(), 1);
  EXPECT_EQ(field_of(t), "heights");  // every vertex a hole
}

}  // namespace
}  // namespace cullcheck
