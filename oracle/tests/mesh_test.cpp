#include "oracle/mesh.hpp"

#include <gtest/gtest.h>

#include "oracle/roof_triangulation.hpp"
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
  // An L-shaped footprint: the roof is the oracle's own triangulation of it.
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

TEST(Mesh, MeshObjectsFollowTheBuildingsWithTheirOwnTrianglesAndOwners) {
  const Opening window{4, 6, 2, 4};
  const MeshObject wall = wall_mesh(20, {10, -5, 0}, {0, 1, 0}, 10, 8, &window);
  const MeshObject tri = mesh_object(30, {{0, 0, 1}, {4, 0, 1}, {0, 4, 1}}, {{0, 1, 2}});
  const Scene scene = scene_of({box_building(7, 0, 0, 10, 5, 12), box_building(8, 20, 0, 30, 5, 12)}, {wall, tri});
  const TriangleMesh mesh = triangulate(scene);
  ASSERT_EQ(mesh.triangles.size(), 10u + 10u + 8u + 1u);
  EXPECT_EQ(mesh.triangles.size(), scene.triangle_count());
  EXPECT_EQ(mesh.building_count, 2u);
  EXPECT_EQ(mesh.object_ids, (std::vector<ObjectId>{7, 8, 20, 30}));
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const std::uint32_t expected_index = t < 10 ? 0 : t < 20 ? 1 : t < 28 ? 2 : 3;
    EXPECT_EQ(mesh.owner_index[t], expected_index) << t;
    EXPECT_EQ(mesh.owner_id[t], mesh.object_ids[expected_index]) << t;
  }
  // The mesh's triangles keep their vertices (and order) as given.
  for (std::size_t k = 0; k < wall.triangles.size(); ++k)
    for (int c = 0; c < 3; ++c) EXPECT_EQ(mesh.vertices[mesh.triangles[20 + k][c]], wall.vertices[wall.triangles[k][c]]);
  EXPECT_EQ(mesh.vertices[mesh.triangles[28][1]], (Vec3{4, 0, 1}));
  // The float origin is near the centre of buildings and meshes together.
  EXPECT_EQ(mesh.origin, (Vec3{15, 0, 0}));
  const Scene meshes_only = scene_of({}, {wall});
  EXPECT_EQ(triangulate(meshes_only).origin, (Vec3{10, 0, 0}));
}

TEST(SurfaceSamples, MeshTrianglesGetVerticesEdgePointsInsetCopiesAndABarycentricGrid) {
  // The longest edge is 4 sqrt 2 = 5.66 m: at 1 m spacing every edge gets 6 intervals, so the
  // samples are 3 x 6 boundary points, as many inset copies, and the (6-1)(6-2)/2 = 10 interior
  // nodes of the barycentric grid.
  const MeshObject m = mesh_object(5, {{0, 0, 1}, {4, 0, 1}, {0, 4, 1}}, {{0, 1, 2}});
  SamplingOptions o;
  o.spacing_m = 1.0;
  const SurfaceSamples s = surface_samples(m, o);
  EXPECT_EQ(s.points.size(), 46u);
  EXPECT_FALSE(s.capped);
  auto has = [&](Vec3 p) {
    for (Vec3 q : s.points)
      if (length(q - p) < 1e-12) return true;
    return false;
  };
  for (Vec3 v : m.vertices) EXPECT_TRUE(has(v));
  EXPECT_TRUE(has({2, 0, 1}));                                      // an edge point
  EXPECT_TRUE(has({2, 2, 1}));                                      // the hypotenuse's midpoint
  EXPECT_TRUE(has({4.0 / 3 * o.inset, 4.0 / 3 * o.inset, 1}));     // vertex (0, 0) moved toward the centroid
  EXPECT_TRUE(has({4 * 2.0 / 6, 4 * 2.0 / 6, 1}));                  // an interior grid node
  for (Vec3 p : s.points) {  // every sample lies on the closed triangle
    EXPECT_EQ(p.z, 1.0);
    EXPECT_GE(p.x, 0.0);
    EXPECT_GE(p.y, 0.0);
    EXPECT_LE(p.x + p.y, 4.0 + 1e-12);
  }
  // The per-object cap widens the spacing as for buildings.
  const MeshObject wall = wall_mesh(6, {0, 0, 0}, {1, 0, 0}, 40, 30);
  o.max_samples_per_building = 200;
  o.spacing_m = 0.5;
  const SurfaceSamples capped = surface_samples(wall, o);
  EXPECT_TRUE(capped.capped);
  EXPECT_LE(capped.points.size(), 200u);
  EXPECT_GT(capped.spacing_m, 0.5);

  // 2,000 triangles (a 40 x 25 grid of 1 m squares) cannot fit 4,096 samples: every triangle is
  // left at its minimum grid of 4 intervals, 12 boundary points, 12 inset copies and 3 interior
  // nodes, at the first spacing beyond the mesh's 40 m extent.
  std::vector<Vec3> v;
  std::vector<std::array<std::uint32_t, 3>> t;
  for (int y = 0; y <= 25; ++y)
    for (int x = 0; x <= 40; ++x) v.push_back({double(x), double(y), 0.5 * ((x + y) % 2)});
  for (std::uint32_t y = 0; y < 25; ++y)
    for (std::uint32_t x = 0; x < 40; ++x) {
      const std::uint32_t a = y * 41 + x;
      t.push_back({a, a + 1, a + 42});
      t.push_back({a, a + 42, a + 41});
    }
  const MeshObject terrain = mesh_object(7, v, t);
  o = SamplingOptions{};
  const SurfaceSamples many = surface_samples(terrain, o);
  EXPECT_TRUE(many.capped);
  EXPECT_EQ(many.points.size(), 2000u * 27u);
  EXPECT_GT(many.spacing_m, 40.0);
  EXPECT_LE(many.spacing_m, 40.0 * 1.25);
}

TEST(SurfaceSamples, HoldCornersEdgesInsetPointsAndRespectTheCap) {
  const Building b = box_building(1, 0, 0, 10, 10, 10);
  SamplingOptions o;
  o.spacing_m = 2.5;
  const SurfaceSamples s = surface_samples(b, triangulate_roof(b.footprint), o);
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
  const SurfaceSamples capped = surface_samples(b, triangulate_roof(b.footprint), o);
  EXPECT_TRUE(capped.capped);
  EXPECT_LE(capped.points.size(), 400u);
  EXPECT_GT(capped.spacing_m, 0.1);
}

}  // namespace
}  // namespace cullcheck::oracle
