// The oracle's own roofs: a constrained triangulation of the footprint, not core's prisms.
#include "oracle/roof_triangulation.hpp"

#include <gtest/gtest.h>

#include <stdexcept>

#include "oracle/mesh.hpp"
#include "test_scenes.hpp"

namespace cullcheck::oracle {
namespace {

using namespace testing;

double area(Vec2 a, Vec2 b, Vec2 c) { return cross(b - a, c - a) / 2; }

// Even-odd point-in-polygon, strict (written here: the test shares nothing with CGAL).
bool strictly_inside(const std::vector<Vec2>& ring, Vec2 p) {
  bool in = false;
  for (std::size_t i = 0, j = ring.size() - 1; i < ring.size(); j = i++) {
    const Vec2 a = ring[i], b = ring[j];
    if ((a.y > p.y) != (b.y > p.y) && p.x < a.x + (p.y - a.y) * (b.x - a.x) / (b.y - a.y)) in = !in;
  }
  return in;
}

// Covers the footprint exactly once: n - 2 counter-clockwise triangles, all inside it (their
// centroids strictly inside), whose areas sum to the footprint's (so they cannot overlap).
double check_roof(const std::vector<Vec2>& ring) {
  const auto triangles = triangulate_roof(ring);
  EXPECT_EQ(triangles.size(), ring.size() - 2);
  double sum = 0;
  for (const auto& t : triangles) {
    const Vec2 a = ring[t[0]], b = ring[t[1]], c = ring[t[2]];
    EXPECT_GT(area(a, b, c), 0.0) << "counter-clockwise, not degenerate";
    EXPECT_TRUE(strictly_inside(ring, (a + b + c) * (1.0 / 3.0))) << "triangle outside the footprint";
    sum += area(a, b, c);
  }
  return sum;
}

TEST(RoofTriangulation, LShapedRoofAreaIsTheFootprintArea) {
  // 20 x 8 plus 8 x 12 = 256 m^2.
  EXPECT_DOUBLE_EQ(check_roof({{0, 0}, {20, 0}, {20, 8}, {8, 8}, {8, 20}, {0, 20}}), 256.0);
}

TEST(RoofTriangulation, UShapedRoofAreaIsTheFootprintArea) {
  // 30 x 20 minus the 10 x 12 courtyard open to the north: 480 m^2.
  EXPECT_DOUBLE_EQ(check_roof({{0, 0}, {30, 0}, {30, 20}, {20, 20}, {20, 8}, {10, 8}, {10, 20}, {0, 20}}), 480.0);
}

TEST(RoofTriangulation, CombAndStarRoofsCoverTheirFootprintsOnce) {
  // A comb: a 40 x 4 spine with four 2 x 10 teeth: 160 + 4 * 20 = 240 m^2.
  std::vector<Vec2> comb{{0, 0}, {40, 0}, {40, 4}};
  for (int k = 3; k >= 0; --k) {
    const double x = 10.0 * k + 4;
    comb.insert(comb.end(), {{x + 2, 4}, {x + 2, 14}, {x, 14}, {x, 4}});
  }
  comb.push_back({0, 4});
  EXPECT_DOUBLE_EQ(check_roof(comb), 240.0);
  // A concave "arrowhead": the triangle (0,0), (10,5), (0,10) minus the notch to (4, 5):
  // 50 - 20 = 30 m^2 (the notch triangle (0,0), (4,5), (0,10) has area 20).
  EXPECT_DOUBLE_EQ(check_roof({{0, 0}, {10, 5}, {0, 10}, {4, 5}}), 30.0);
}

TEST(RoofTriangulation, RejectsFootprintsItCannotCoverOnce) {
  EXPECT_THROW(triangulate_roof({{0, 0}, {1, 0}}), std::invalid_argument);
  EXPECT_THROW(triangulate_roof({{0, 0}, {10, 0}, {10, 10}, {0, 0}, {0, 10}}), std::invalid_argument);  // repeated vertex
  EXPECT_THROW(triangulate_roof({{0, 0}, {10, 10}, {10, 0}, {0, 10}}), std::invalid_argument);          // bow tie
}

TEST(RoofTriangulation, MeshRoofComesFromTheFootprintNotFromCorePrisms) {
  // Core's prisms deliberately wrong (only half the L): the oracle's roof still covers the
  // whole footprint, because it never reads them.
  Building l = polygon_building(3, {{0, 0}, {20, 0}, {20, 8}, {8, 8}, {8, 20}, {0, 20}}, 15);
  l.prisms = {ConvexVerticalPrism{{{0, 0}, {20, 0}, {20, 8}, {0, 8}}, 15}};
  const TriangleMesh mesh = triangulate(scene_of({l}));
  double roof = 0;
  std::size_t roof_triangles = 0;
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const Vec3 a = mesh.vertices[mesh.triangles[t][0]], b = mesh.vertices[mesh.triangles[t][1]],
               c = mesh.vertices[mesh.triangles[t][2]];
    if (a.z != 15 || b.z != 15 || c.z != 15) continue;
    ++roof_triangles;
    roof += area(plan(a), plan(b), plan(c));
  }
  EXPECT_EQ(roof_triangles, 4u);
  EXPECT_DOUBLE_EQ(roof, 256.0);
  ASSERT_EQ(mesh.roofs.size(), 1u);
  EXPECT_EQ(mesh.roofs[0].size(), 4u);
}

}  // namespace
}  // namespace cullcheck::oracle
