#include "oracle/mesh.hpp"

#include <gtest/gtest.h>

#include "oracle/surface_samples.hpp"
#include "test_scenes.hpp"

namespace cullcheck::oracle {
namespace {

using namespace testing;

double triangle_area_xy(const TriangleMesh& m, std::size_t t) {
  const Vec3 a = m.vertices[m.triangles[t][0]], b = m.vertices[m.triangles[t][1]], c = m.vertices[m.triangles[t][2]];
  return cross(plan(b) - plan(a), plan(c) - plan(a)) / 2;
}

TEST(Mesh, RectangleHasTwoTrianglesPerWallAndTwoOnTheRoof) {
  const Scene scene = scene_of({box_building(7, 0, 0, 10, 5, 12)});
  const TriangleMesh mesh = triangulate(scene);
  ASSERT_EQ(mesh.triangles.size(), 10u);
  EXPECT_EQ(mesh.triangles.size(), scene.triangle_count());
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    EXPECT_EQ(mesh.owner_id[t], 7u);
    EXPECT_EQ(mesh.owner_index[t], 0u);
  }
}

TEST(Mesh, NonConvexRoofIsCoveredExactlyOnceAndWallsFaceOutward) {
  // An L-shaped footprint: the roof comes from its convex prisms, fanned.
  const Building l = polygon_building(3, {{0, 0}, {20, 0}, {20, 8}, {8, 8}, {8, 20}, {0, 20}}, 15);
  const Scene scene = scene_of({box_building(1, 40, 0, 50, 10, 5), l});
  const TriangleMesh mesh = triangulate(scene);
  EXPECT_EQ(mesh.triangles.size(), scene.triangle_count());
  double roof_area = 0;
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    if (mesh.owner_id[t] != 3) continue;
    const Vec3 a = mesh.vertices[mesh.triangles[t][0]], b = mesh.vertices[mesh.triangles[t][1]],
               c = mesh.vertices[mesh.triangles[t][2]];
    const Vec3 normal = cross(b - a, c - a);
    if (a.z == 15 && b.z == 15 && c.z == 15) {
      EXPECT_GT(normal.z, 0) << "roof triangles face up";
      roof_area += triangle_area_xy(mesh, t);
    } else {
      EXPECT_EQ(normal.z, 0);
      // Outward: the normal points away from the footprint's interior point (4, 4).
      const Vec3 centre{4, 4, a.z};
      EXPECT_GT(dot(normal, a - centre) + dot(normal, b - centre), 0);
    }
  }
  EXPECT_DOUBLE_EQ(roof_area, signed_area(l.footprint));
}

TEST(Mesh, EmptySceneGivesEmptyMesh) {
  EXPECT_TRUE(triangulate(Scene{}).triangles.empty());
}

TEST(SurfaceSamples, HoldCornersEdgesInsetPointsAndRespectTheCap) {
  const Building b = box_building(1, 0, 0, 10, 10, 10);
  SamplingOptions o;
  o.spacing_m = 2.5;
  const SurfaceSamples s = surface_samples(b, o);
  auto has = [&](Vec3 p) {
    for (Vec3 q : s.points)
      if (length(q - p) < 1e-12) return true;
    return false;
  };
  EXPECT_TRUE(has({0, 0, 0}));
  EXPECT_TRUE(has({10, 10, 10}));
  EXPECT_TRUE(has({5, 0, 10}));                        // top edge midpoint
  EXPECT_TRUE(has({10 * o.inset, 0, 10 * o.inset}));  // bottom corner moved into the wall
  EXPECT_TRUE(has({5, 5, 10}));                        // roof grid
  EXPECT_FALSE(s.capped);
  o.max_samples_per_building = 400;
  o.spacing_m = 0.1;
  const SurfaceSamples capped = surface_samples(b, o);
  EXPECT_TRUE(capped.capped);
  EXPECT_LE(capped.points.size(), 400u);
  EXPECT_GT(capped.spacing_m, 0.1);
}

}  // namespace
}  // namespace cullcheck::oracle
