// Minkowski shrinking of general meshes (slice paper §4.1.2-4.1.4, engine/shrinking/
// minkowski_mesh.hpp) on meshes whose answer is known: how far each face moves, which faces
// collide, where ground vertices go; and the 2.5D occluder shrink_minkowski derives from it.
#include <gtest/gtest.h>

#include <cmath>
#include <map>

#include "engine/shrinking/minkowski_mesh.hpp"
#include "engine/shrinking/minkowski_shrinking.hpp"
#include "engine/shrinking/region_shrinking.hpp"

namespace cullcheck {
namespace {

Building building_of(std::vector<Vec2> footprint, double height) {
  Building b;
  b.footprint = std::move(footprint);
  b.height = height;
  finish_building(b);
  return b;
}

Building box(double x0, double y0, double w, double d, double h) {
  return building_of({{x0, y0}, {x0 + w, y0}, {x0 + w, y0 + d}, {x0, y0 + d}}, h);
}

// How far behind its original plane each moved vertex of each kept face lies: [min, max].
std::pair<double, double> face_motion_range(const TriangleMesh& original, const ShrunkMesh& shrunk) {
  double lo = HUGE_VAL, hi = -HUGE_VAL;
  for (const auto& tri : shrunk.mesh.triangles) {
    const Vec3 a = original.vertices[tri[0]];
    const Vec3 n = normalized(cross(original.vertices[tri[1]] - a, original.vertices[tri[2]] - a));
    for (std::uint32_t v : tri) {
      const double depth = dot(a - shrunk.mesh.vertices[v], n);
      lo = std::min(lo, depth), hi = std::max(hi, depth);
    }
  }
  return {lo, hi};
}

TEST(MinkowskiMesh, BuildingMeshIsClosedAboveTheGround) {
  const Building l = building_of({{0, 0}, {20, 0}, {20, 8}, {8, 8}, {8, 20}, {0, 20}}, 12);
  const TriangleMesh mesh = building_mesh(l);
  EXPECT_EQ(mesh.triangles.size(), l.triangle_count());
  // Every edge is shared by exactly two triangles, except the floorless ground ring (one each).
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> uses;
  for (const auto& t : mesh.triangles)
    for (int c = 0; c < 3; ++c) ++uses[std::minmax(t[c], t[(c + 1) % 3])];
  for (const auto& [edge, count] : uses) {
    const bool ground = edge.first < 6 && edge.second < 6;
    EXPECT_EQ(count, ground ? 1 : 2) << edge.first << "-" << edge.second;
  }
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const Vec3 n = mesh.normal(t);
    EXPECT_NEAR(n.z, t >= 12 ? 1.0 : 0.0, 1e-15);  // roof, walls
  }
}

// A box: every face moves exactly ε, the roof drops ε, ground vertices stay on the ground, and
// every vertex moves by ε√3 (roof corners) or ε√2 (ground corners).
TEST(MinkowskiMesh, BoxFacesMoveExactlyEpsilon) {
  const double eps = 0.5;
  const Building b = box(103.25, -41.5, 10, 6, 8);
  const TriangleMesh mesh = building_mesh(b);
  const ShrunkMesh shrunk = shrink_mesh(mesh, eps);
  EXPECT_EQ(shrunk.stats.faces_removed, 0u);
  EXPECT_EQ(shrunk.mesh.triangles.size(), mesh.triangles.size());
  const auto [lo, hi] = face_motion_range(mesh, shrunk);
  EXPECT_NEAR(lo, eps, 1e-12);
  EXPECT_NEAR(hi, eps, 1e-12);
  for (std::size_t v = 0; v < 4; ++v) {
    EXPECT_EQ(shrunk.mesh.vertices[v].z, 0.0);
    EXPECT_NEAR(shrunk.delta[v], eps * std::sqrt(2.0), 1e-12);
  }
  for (std::size_t v = 4; v < 8; ++v) {
    EXPECT_NEAR(shrunk.mesh.vertices[v].z, 8 - eps, 1e-12);
    EXPECT_NEAR(shrunk.delta[v], eps * std::sqrt(3.0), 1e-12);
  }
  EXPECT_NEAR(shrunk.stats.max_delta, eps * std::sqrt(3.0), 1e-12);
}

// Non-right angles: a 20-degree wedge and an obtuse triangle. Every face moves at least ε; at the
// wedge's tip the roof drops by ε / (1 + cos θ) with θ the angle between the walls' normals.
TEST(MinkowskiMesh, NonRightPrismsMoveEveryFaceAtLeastEpsilon) {
  const double eps = 0.4;
  const double tip = 20.0 * kPi / 180;
  const Building wedge = building_of({{0, 0}, {60 * std::cos(tip / 2), -60 * std::sin(tip / 2)},
                                      {60 * std::cos(tip / 2), 60 * std::sin(tip / 2)}}, 15);
  const Building obtuse = building_of({{0, 0}, {30, 0}, {-5, 12}}, 20);
  for (const Building* b : {&wedge, &obtuse}) {
    const TriangleMesh mesh = building_mesh(*b);
    const ShrunkMesh shrunk = shrink_mesh(mesh, eps);
    EXPECT_EQ(shrunk.stats.faces_removed, 0u);
    const auto [lo, hi] = face_motion_range(mesh, shrunk);
    EXPECT_GE(lo, eps - 1e-12);
    EXPECT_GT(hi, eps);  // some face moves more: the price of one δ per vertex
    for (std::size_t v = 0; v < 3; ++v) EXPECT_EQ(shrunk.mesh.vertices[v].z, 0.0);
  }
  // The cost of the literal rule: a triangle with an 8.5-degree corner, 9 m tall, drops that
  // corner's roof vertex 36 m for ε = 0.4 m, below the ground, and its walls turn over.
  const ShrunkMesh sharp = shrink_mesh(building_mesh(building_of({{0, 0}, {30, 0}, {-10, 6}}, 9)), eps);
  EXPECT_GT(sharp.stats.flipped_removed, 0u);
  EXPECT_LT(sharp.mesh.vertices[4].z, 0.0);

  const ShrunkMesh shrunk = shrink_mesh(building_mesh(wedge), eps);
  const double cos_theta = std::cos(kPi - tip);  // the tip's walls' normals are 160 degrees apart
  EXPECT_NEAR(15 - shrunk.mesh.vertices[3].z, eps / (1 + cos_theta), 1e-9);
  // The tip is the sharpest corner, so its roof vertex drops most (6.6 m here, against ε = 0.4).
  EXPECT_LE(shrunk.mesh.vertices[3].z, std::min(shrunk.mesh.vertices[4].z, shrunk.mesh.vertices[5].z));
}

// A slab thinner than 2ε: its long walls' movement volumes cross, so faces are removed; a
// slab thicker than 2ε keeps every face.
TEST(MinkowskiMesh, ThinSlabLosesFaces) {
  const ShrunkMesh thin = shrink_mesh(building_mesh(box(0, 0, 20, 0.8, 10)), 0.5);
  EXPECT_GT(thin.stats.collisions_removed, 0u);
  EXPECT_EQ(thin.stats.faces_removed, thin.stats.collisions_removed + thin.stats.zero_area_removed +
                                          thin.stats.flipped_removed + thin.stats.unshrinkable_removed);
  const ShrunkMesh thick = shrink_mesh(building_mesh(box(0, 0, 20, 1.2, 10)), 0.5);
  EXPECT_EQ(thick.stats.faces_removed, 0u);
  EXPECT_GT(thick.stats.pairs_tested, 0u);
}

// A U whose arms are thinner than 2ε: the faces on either side of an arm collide. With thick
// arms the facing inner walls move apart (they face each other across the outside) and nothing
// is removed.
TEST(MinkowskiMesh, UShapeWithThinArmsLosesFaces) {
  auto u_shape = [](double arm) {
    return building_of({{0, 0}, {20, 0}, {20, 20}, {20 - arm, 20}, {20 - arm, arm}, {arm, arm}, {arm, 20}, {0, 20}}, 10);
  };
  const ShrunkMesh thin = shrink_mesh(building_mesh(u_shape(0.6)), 0.5);
  EXPECT_GT(thin.stats.collisions_removed, 0u);
  const ShrunkMesh thick = shrink_mesh(building_mesh(u_shape(4.0)), 0.5);
  EXPECT_EQ(thick.stats.faces_removed, 0u);
  const auto [lo, hi] = face_motion_range(building_mesh(u_shape(4.0)), thick);
  EXPECT_NEAR(lo, 0.5, 1e-12);
  EXPECT_NEAR(hi, 0.5, 1e-12);
}

// A square ring (torus-like: a frame around a courtyard, built as a closed mesh by hand): when
// its bars are thinner than 2ε the inner and outer walls collide.
TriangleMesh square_frame(double outer, double bar, double h) {
  TriangleMesh m;
  const double a = bar, b = outer - bar;
  const std::vector<Vec2> out_ring{{0, 0}, {outer, 0}, {outer, outer}, {0, outer}};
  const std::vector<Vec2> in_ring{{a, a}, {b, a}, {b, b}, {a, b}};
  for (Vec2 p : out_ring) m.vertices.push_back({p.x, p.y, 0});    // 0-3
  for (Vec2 p : out_ring) m.vertices.push_back({p.x, p.y, h});    // 4-7
  for (Vec2 p : in_ring) m.vertices.push_back({p.x, p.y, 0});     // 8-11
  for (Vec2 p : in_ring) m.vertices.push_back({p.x, p.y, h});     // 12-15
  for (std::uint32_t i = 0; i < 4; ++i) {
    const std::uint32_t j = (i + 1) % 4;
    m.triangles.push_back({i, j, 4 + j});  // outer walls face out
    m.triangles.push_back({i, 4 + j, 4 + i});
    m.triangles.push_back({8 + j, 8 + i, 12 + i});  // inner walls face the courtyard
    m.triangles.push_back({8 + j, 12 + i, 12 + j});
    m.triangles.push_back({4 + i, 4 + j, 12 + j});  // roof strip between the rings
    m.triangles.push_back({4 + i, 12 + j, 12 + i});
  }
  return m;
}

TEST(MinkowskiMesh, SquareFrameBarsCollideWhenThin) {
  const TriangleMesh wide = square_frame(30, 5, 10);
  for (std::size_t t = 0; t < wide.triangles.size(); ++t) {
    const Vec3 n = wide.normal(t);
    const std::size_t kind = t % 6;
    if (kind >= 4) {
      EXPECT_NEAR(n.z, 1.0, 1e-15);
    }
  }
  const ShrunkMesh ok = shrink_mesh(wide, 0.5);
  EXPECT_EQ(ok.stats.faces_removed, 0u);
  const auto [lo, hi] = face_motion_range(wide, ok);
  EXPECT_NEAR(lo, 0.5, 1e-12);
  EXPECT_NEAR(hi, 0.5, 1e-12);
  const ShrunkMesh thin = shrink_mesh(square_frame(30, 0.7, 10), 0.5);
  EXPECT_GT(thin.stats.collisions_removed, 0u);
}

// A general closed mesh off the ground: a regular octahedron moves every face by exactly ε (each
// vertex by ε√3); a square pyramid standing on the ground keeps its base on the ground and still
// moves its sloped faces by at least ε (δ recomputed with the horizontal part of the normal).
TEST(MinkowskiMesh, OctahedronAndPyramid) {
  TriangleMesh octahedron;
  octahedron.vertices = {{10, 0, 50}, {-10, 0, 50}, {0, 10, 50}, {0, -10, 50}, {0, 0, 60}, {0, 0, 40}};
  octahedron.triangles = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4}, {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
  const ShrunkMesh o = shrink_mesh(octahedron, 1.0);
  EXPECT_EQ(o.stats.faces_removed, 0u);
  const auto [o_lo, o_hi] = face_motion_range(octahedron, o);
  EXPECT_NEAR(o_lo, 1.0, 1e-12);
  EXPECT_NEAR(o_hi, 1.0, 1e-12);
  EXPECT_NEAR(o.stats.max_delta, std::sqrt(3.0), 1e-12);

  TriangleMesh pyramid;  // with a floor, which is not required to move
  pyramid.vertices = {{0, 0, 0}, {10, 0, 0}, {10, 10, 0}, {0, 10, 0}, {5, 5, 12}};
  pyramid.triangles = {{0, 1, 4}, {1, 2, 4}, {2, 3, 4}, {3, 0, 4}, {0, 2, 1}, {0, 3, 2}};
  const ShrunkMesh p = shrink_mesh(pyramid, 0.5);
  EXPECT_EQ(p.stats.faces_removed, 0u);
  for (std::size_t v = 0; v < 4; ++v) EXPECT_EQ(p.mesh.vertices[v].z, 0.0);
  TriangleMesh sides = pyramid;
  sides.triangles.resize(4);
  ShrunkMesh p_sides = p;
  p_sides.mesh.triangles.resize(4);
  const auto [p_lo, p_hi] = face_motion_range(sides, p_sides);
  EXPECT_GE(p_lo, 0.5 - 1e-12);
  EXPECT_GT(p.mesh.vertices[4].z, 0.0);
  EXPECT_LT(p.mesh.vertices[4].z, 12.0 - 0.5);
  (void)p_hi;
}

// A vertex whose faces' normals span more than a hemisphere has no finite δ: a flat "tent" folded
// back on itself is not a solid; the faces around such a vertex are removed, never moved outward.
TEST(MinkowskiMesh, VertexWithoutFiniteDeltaRemovesItsFaces) {
  TriangleMesh two_sided;
  two_sided.vertices = {{0, 0, 5}, {10, 0, 5}, {0, 10, 5}};
  two_sided.triangles = {{0, 1, 2}, {0, 2, 1}};
  const ShrunkMesh s = shrink_mesh(two_sided, 0.5);
  EXPECT_EQ(s.stats.unshrinkable_removed, 2u);
  EXPECT_TRUE(s.mesh.triangles.empty());
}

// The 2.5D occluder of shrink_minkowski: a box becomes the box inset by ε (plus the 1e-9 pad) and
// ε lower; an L shrinks as a whole, so it keeps more area than shrink_former's CVP-by-CVP offset;
// a slab thinner than 2ε is no occluder.
TEST(MinkowskiOccluder, BoxLShapeAndSlab) {
  const double eps = 0.5;
  const MinkowskiOccluder b = minkowski_occluder(box(0, 0, 10, 6, 8), eps);
  ASSERT_EQ(b.outcome, MinkowskiOutcome::occluder);
  EXPECT_NEAR(b.height, 8 - eps, 1e-12);
  EXPECT_NEAR(signed_area(b.footprint), 9 * 5, 1e-6);

  const Building l = building_of({{0, 0}, {20, 0}, {20, 8}, {8, 8}, {8, 20}, {0, 20}}, 12);
  ASSERT_GT(l.prisms.size(), 1u);
  const MinkowskiOccluder m = minkowski_occluder(l, eps);
  ASSERT_EQ(m.outcome, MinkowskiOutcome::occluder);
  double former = 0.0;
  for (const ConvexVerticalPrism& prism : l.prisms) {
    const auto ring = shrink_convex_ring(prism.ring, eps);
    if (ring) former += signed_area(*ring);
  }
  const double whole = signed_area(m.footprint);
  EXPECT_NEAR(whole, 19 * 7 + 7 * 12, 1e-6);  // the L inset by ε: 19 x 7 plus 7 x 12
  EXPECT_GT(whole, former);
  EXPECT_FALSE(m.prisms.empty());

  EXPECT_EQ(minkowski_occluder(box(0, 0, 20, 0.8, 10), eps).outcome, MinkowskiOutcome::faces_removed);
  EXPECT_NE(minkowski_occluder(box(0, 0, 20, 5, 0.4), eps).outcome, MinkowskiOutcome::occluder);  // lower than ε
}

}  // namespace
}  // namespace cullcheck
