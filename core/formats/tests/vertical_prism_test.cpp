// Prism detection (as_vertical_prism) on hand-made meshes: yes for prisms however they are
// triangulated (a triangle soup with mixed winding, a floor), no for everything that is not one
// (a hole in the roof, a pyramid, a box off the ground, a missing wall triangle, an overhang).
#include <gtest/gtest.h>

#include <map>

#include "core/formats/mesh_formats.hpp"
#include "core/scene_io.hpp"

namespace cullcheck::formats {
namespace {

// An L of 2 m cells: x in [0, 10] for y in [0, 4], plus x in [0, 4] for y in [4, 10].
bool in_l(int i, int j) { return (j < 2 && i < 5) || (i < 2 && j < 5); }
const std::vector<Vec2> kL = {{0, 0}, {10, 0}, {10, 4}, {4, 4}, {4, 10}, {0, 10}};

class Soup {
 public:
  // Every triangle gets vertices of its own; every other one is wound the other way.
  void triangle(Vec3 a, Vec3 b, Vec3 c) {
    const auto base = static_cast<std::uint32_t>(mesh.vertices.size());
    mesh.vertices.insert(mesh.vertices.end(), {a, b, c});
    flip_ = !flip_;
    if (flip_) mesh.triangles.push_back({base, base + 2, base + 1});
    else mesh.triangles.push_back({base, base + 1, base + 2});
  }
  void quad(Vec3 a, Vec3 b, Vec3 c, Vec3 d) { triangle(a, b, c), triangle(a, c, d); }
  MeshObject mesh;

 private:
  bool flip_ = false;
};

// The L prism of height h as a soup: the roof (and optionally floor) cell by cell, each wall
// split at every 2 m like the roof, from z0 to h.
Soup l_prism(double h, bool hole_in_roof = false, bool floor = false, double z0 = 0.0) {
  Soup s;
  for (int i = 0; i < 5; ++i)
    for (int j = 0; j < 5; ++j) {
      if (!in_l(i, j)) continue;
      const double x = 2.0 * i, y = 2.0 * j;
      if (!(hole_in_roof && i == 1 && j == 1)) s.quad({x, y, h}, {x + 2, y, h}, {x + 2, y + 2, h}, {x, y + 2, h});
      if (floor) s.quad({x, y, z0}, {x, y + 2, z0}, {x + 2, y + 2, z0}, {x + 2, y, z0});
    }
  for (std::size_t e = 0; e < kL.size(); ++e) {
    const Vec2 a = kL[e], b = kL[(e + 1) % kL.size()];
    const int steps = static_cast<int>(length(b - a) / 2.0 + 0.5);
    for (int k = 0; k < steps; ++k) {
      const Vec2 p = a + (b - a) * (double(k) / steps), q = a + (b - a) * (double(k + 1) / steps);
      s.quad({p.x, p.y, z0}, {q.x, q.y, z0}, {q.x, q.y, h}, {p.x, p.y, h});
    }
  }
  return s;
}

bool same_ring(const std::vector<Vec2>& a, const std::vector<Vec2>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t shift = 0; shift < a.size(); ++shift) {
    bool all = true;
    for (std::size_t i = 0; i < a.size() && all; ++i) all = length(a[i] - b[(i + shift) % b.size()]) <= 1e-9;
    if (all) return true;
  }
  return false;
}

TEST(VerticalPrism, LShapedTriangleSoupIsAPrism) {
  MeshObject m = l_prism(7.5).mesh;
  m.id = 11;
  const auto b = as_vertical_prism(m);
  ASSERT_TRUE(b.has_value());
  EXPECT_EQ(b->id, 11u);
  EXPECT_EQ(b->height, 7.5);
  EXPECT_TRUE(same_ring(b->footprint, kL));  // collinear cell corners merged away
  EXPECT_EQ(b->prisms.size(), 2u);           // validated and partitioned like any building
}

TEST(VerticalPrism, AFloorOfTheSameOutlineIsAllowed) {
  EXPECT_TRUE(as_vertical_prism(l_prism(3.0, false, true).mesh).has_value());
}

TEST(VerticalPrism, AHoleInTheRoofIsNot) { EXPECT_FALSE(as_vertical_prism(l_prism(7.5, true).mesh).has_value()); }

TEST(VerticalPrism, ABoxOffTheGroundIsNot) {
  EXPECT_FALSE(as_vertical_prism(l_prism(3.0, false, true, 1.0).mesh).has_value());
}

TEST(VerticalPrism, APyramidIsNot) {
  MeshObject m;
  m.vertices = {{0, 0, 0}, {4, 0, 0}, {4, 4, 0}, {0, 4, 0}, {2, 2, 5}};
  m.triangles = {{0, 1, 4}, {1, 2, 4}, {2, 3, 4}, {3, 0, 4}, {0, 2, 1}, {0, 3, 2}};
  EXPECT_FALSE(as_vertical_prism(m).has_value());
}

TEST(VerticalPrism, AMissingWallTriangleIsNot) {
  MeshObject m = l_prism(7.5).mesh;
  m.triangles.pop_back();
  EXPECT_FALSE(as_vertical_prism(m).has_value());
}

TEST(VerticalPrism, ADuplicatedRoofTriangleIsNot) {
  MeshObject m = l_prism(7.5).mesh;
  m.triangles.push_back(m.triangles.front());
  EXPECT_FALSE(as_vertical_prism(m).has_value());
}

// A box whose roof overhangs its walls (an arcade's slab): the walls do not stand on the outline.
TEST(VerticalPrism, AnOverhangIsNot) {
  Soup s;
  s.quad({-1, -1, 4}, {5, -1, 4}, {5, 5, 4}, {-1, 5, 4});
  const Vec2 ring[4] = {{0, 0}, {4, 0}, {4, 4}, {0, 4}};
  for (int e = 0; e < 4; ++e) {
    const Vec2 a = ring[e], b = ring[(e + 1) % 4];
    s.quad({a.x, a.y, 0}, {b.x, b.y, 0}, {b.x, b.y, 4}, {a.x, a.y, 4});
  }
  EXPECT_FALSE(as_vertical_prism(s.mesh).has_value());
}

// Every building cullcheck exports is recognised with its own footprint, exactly when the
// vertices are doubles; the thesis testbed's 16-gon and a U-shape too.
TEST(VerticalPrism, ExportedBuildingsAreRecognised) {
  Building u;
  u.id = 2;
  u.height = 12.25;
  u.footprint = {{0, 0}, {9, 0}, {9, 7}, {6, 7}, {6, 3}, {3, 3}, {3, 7}, {0, 7}};
  validate_and_finish(u);
  Building g;
  g.id = 5;
  g.height = 30;
  g.footprint = {{3, 0}, {17, 0}, {18.8, 0.6}, {19.4, 1.2}, {20, 3}, {20, 17}, {19.4, 18.8}, {18.8, 19.4},
                 {17, 20}, {3, 20}, {1.2, 19.4}, {0.6, 18.8}, {0, 17}, {0, 3}, {0.6, 1.2}, {1.2, 0.6}};
  validate_and_finish(g);
  for (const Building& b : {u, g}) {
    const auto p = as_vertical_prism(exported_mesh(b));
    ASSERT_TRUE(p.has_value()) << b.id;
    EXPECT_TRUE(same_ring(p->footprint, b.footprint)) << b.id;
    EXPECT_EQ(p->height, b.height);
  }
}

}  // namespace
}  // namespace cullcheck::formats
