// The slice-wise structure (engine/slice_wise/slicing.hpp, Yılmaz & Güdükbay sections 3.2-3.3):
// every triangle in at least one slice on each axis and exactly in the slabs its extent meets;
// the three signed indices of Fig. 5 select the slices they say; the rendering set of "all
// visible" is the whole object and of an L-shape the union of its two parts.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <vector>

#include "engine/slice_wise/cell_culling.hpp"
#include "engine/slice_wise/slice_rectangle.hpp"
#include "engine/slice_wise/slice_scene.hpp"
#include "engine/slice_wise/slicing.hpp"
#include "engine/slice_wise/solid_parts.hpp"
#include "engine/slice_wise/voxel_erosion.hpp"
#include "generators/detailed_buildings.hpp"

namespace cullcheck::slice_wise {
namespace {

MeshObject tower() {
  generators::DetailedCityParams p;
  return generators::detailed_building(7, {0, 0}, {20, 14}, 45.0, p, 3);
}

double coordinate(Vec3 v, int axis) { return axis == 0 ? v.x : axis == 1 ? v.y : v.z; }

TEST(Slicing, EveryTriangleLiesInTheSlicesItsExtentMeets) {
  const MeshObject m = tower();
  const SlicedObject s = slice_object(m);
  ASSERT_GT(m.triangles.size(), 100u);
  for (int axis = 0; axis < 3; ++axis) {
    const AxisSlices& a = s.axes[static_cast<std::size_t>(axis)];
    EXPECT_GE(a.count(), 1u);
    EXPECT_LE(a.count(), 32u);
    std::vector<int> slices_of(m.triangles.size(), 0);
    for (std::size_t i = 0; i < a.count(); ++i) {
      const double lo = a.origin + a.slab[i] * a.thickness, hi = lo + a.thickness;
      for (std::uint32_t k = a.begin[i]; k < a.begin[i + 1]; ++k) {
        const auto& t = m.triangles[a.triangles[k]];
        double tlo = HUGE_VAL, thi = -HUGE_VAL;
        for (std::uint32_t v : t) tlo = std::min(tlo, coordinate(m.vertices[v], axis)), thi = std::max(thi, coordinate(m.vertices[v], axis));
        EXPECT_LE(tlo, hi + 1e-9) << "axis " << axis << " slice " << i;
        EXPECT_GE(thi, lo - 1e-9) << "axis " << axis << " slice " << i;
        ++slices_of[a.triangles[k]];
      }
    }
    for (std::size_t t = 0; t < m.triangles.size(); ++t) EXPECT_GE(slices_of[t], 1) << "axis " << axis << " triangle " << t;
  }
  // 20 x 14 x 45 m at the default 2 m slabs (the paper's slices are as wide as its view cells):
  // 10, 7 and 23 slices; at 3 m, 7, 5 and 15.
  EXPECT_EQ(s.axes[0].count(), 10u);
  EXPECT_EQ(s.axes[1].count(), 7u);
  EXPECT_EQ(s.axes[2].count(), 23u);
  const SlicedObject thick = slice_object(m, SlicingOptions{32, 3.0});
  EXPECT_EQ(thick.axes[0].count(), 7u);
  EXPECT_EQ(thick.axes[1].count(), 5u);
  EXPECT_EQ(thick.axes[2].count(), 15u);
}

TEST(Slicing, IndicesSelectTheSlicesFigureFiveSays) {
  const SlicedObject s = slice_object(tower());
  VisibilityIndices v;
  v.x = 2;  // occluded from the right: slices 0..2 visible
  EXPECT_TRUE(slice_visible(s, v, 0, 2));
  EXPECT_FALSE(slice_visible(s, v, 0, 3));
  v.x = -4;  // occluded from the left: slices 4.. visible
  EXPECT_FALSE(slice_visible(s, v, 0, 3));
  EXPECT_TRUE(slice_visible(s, v, 0, 4));
  v.z = 5;  // occluded from below: slices 5.. visible
  EXPECT_FALSE(slice_visible(s, v, 2, 4));
  EXPECT_TRUE(slice_visible(s, v, 2, 5));
}

TEST(Slicing, RenderingSetsOfAllVisibleAndOfAnLShape) {
  const MeshObject m = tower();
  const SlicedObject s = slice_object(m);
  EXPECT_EQ(rendering_set(s, all_visible(s)).size(), m.triangles.size());
  // L-shape: the lower left hidden (x slices 0..3, z slices 0..9), the rest drawn.
  VisibilityIndices v;
  v.x = -4, v.z = 10, v.work_axis = 0;
  const std::vector<std::uint32_t> drawn = rendering_set(s, v);
  EXPECT_LT(drawn.size(), m.triangles.size());
  EXPECT_TRUE(std::is_sorted(drawn.begin(), drawn.end()));
  // Each drawn triangle reaches x slice 4 or beyond, or z slice 10 or beyond; each such
  // triangle is drawn.
  const double x4 = s.axes[0].origin + s.axes[0].slab[4] * s.axes[0].thickness;
  const double z10 = s.axes[2].origin + s.axes[2].slab[10] * s.axes[2].thickness;
  std::size_t expected = 0;
  for (std::uint32_t t = 0; t < m.triangles.size(); ++t) {
    double xmax = -HUGE_VAL, zmax = -HUGE_VAL;
    for (std::uint32_t k : m.triangles[t]) xmax = std::max(xmax, m.vertices[k].x), zmax = std::max(zmax, m.vertices[k].z);
    const bool want = xmax >= x4 - 1e-9 || zmax >= z10 - 1e-9;
    expected += want;
    EXPECT_EQ(std::binary_search(drawn.begin(), drawn.end(), t), want) << "triangle " << t;
  }
  EXPECT_EQ(drawn.size(), expected);
}

// Both vertical indices at once (work axis 2): a triangle is drawn when it reaches a visible z
// slice, or a visible x slice and a visible y slice.
TEST(Slicing, TheRenderingSetOfBothVerticalAxesDropsTheUnionOfTheirRectangles) {
  const MeshObject m = tower();
  const SlicedObject s = slice_object(m);
  VisibilityIndices v = all_visible(s);
  v.x = -3, v.y = 2, v.z = 8, v.work_axis = kBothVerticalAxes;  // x slices 0..2 and y slices 3.. hidden below z slice 8
  const std::vector<std::uint32_t> drawn = rendering_set(s, v);
  const double x3 = s.axes[0].origin + s.axes[0].slab[3] * s.axes[0].thickness;
  const double y3 = s.axes[1].origin + s.axes[1].slab[3] * s.axes[1].thickness;
  const double z8 = s.axes[2].origin + s.axes[2].slab[8] * s.axes[2].thickness;
  std::size_t expected = 0, in_both = 0;
  for (std::uint32_t t = 0; t < m.triangles.size(); ++t) {
    Box3 b;
    for (std::uint32_t k : m.triangles[t]) b.extend(m.vertices[k]);
    const bool x_hidden = b.hi.x < x3 - 1e-9, y_hidden = b.lo.y > y3 + 1e-9, z_hidden = b.hi.z < z8 - 1e-9;
    const bool want = !(z_hidden && (x_hidden || y_hidden));
    expected += want;
    in_both += z_hidden && x_hidden && y_hidden;
    EXPECT_EQ(std::binary_search(drawn.begin(), drawn.end(), t), want) << "triangle " << t;
  }
  EXPECT_EQ(drawn.size(), expected);
  EXPECT_GT(in_both, 0u) << "the two rectangles overlap at the corner";
  EXPECT_EQ(m.triangles.size() - expected, 339u);
  // Each axis alone drops less than both.
  v.work_axis = 0;
  EXPECT_GT(rendering_set(s, v).size(), drawn.size());
  v.work_axis = 1;
  EXPECT_GT(rendering_set(s, v).size(), drawn.size());
}

// One object's SliceWiseObject (slices, per-triangle ranges) through the scene preparation.
// Sliced in 3 m slabs (7 x 5 x 15 slices for the tower), which the occlusion below is written for.
SliceWiseObject prepared_object(const MeshObject& m) {
  Scene scene;
  scene.meshes.push_back(m);
  SliceSceneOptions so;
  so.slicing.slice_m = 3.0;
  const SliceWiseScene prepared(scene, so);
  return prepared.objects()[0];
}

TEST(Algorithm3, DropsExactlyTheTrianglesItsIndicesDrop) {
  const MeshObject m = tower();
  const SliceWiseObject o = prepared_object(m);
  const std::size_t nx = o.slices.axes[0].count(), ny = o.slices.axes[1].count(), nz = o.slices.axes[2].count();
  ASSERT_EQ(nx, 7u);
  ASSERT_EQ(ny, 5u);
  ASSERT_EQ(nz, 15u);
  SliceOcclusion occ;
  occ.hidden_height[0] = {20, 20, 20, 0, 0, 0, 0};  // the three lowest-x slices hidden to 20 m: an L from the low side
  occ.hidden_height[1].assign(ny, 0.0);
  occ.z_hidden.assign(nz, 0);
  const SliceChoice c = choose_slices(o, occ);
  EXPECT_EQ(c.indices.work_axis, 0);
  EXPECT_EQ(c.indices.x, -3) << "slices 3.. stay";
  EXPECT_EQ(c.indices.z, 6) << "slabs of 3 m: six lie below 20 m";
  EXPECT_EQ(c.form, VisibleForm::l_shaped);
  EXPECT_TRUE(c.any_hidden_cell);
  EXPECT_EQ(c.dropped, m.triangles.size() - rendering_set(o.slices, c.indices).size());
  EXPECT_GT(c.dropped, 0u);
  EXPECT_EQ(c.cell_dropped, c.dropped) << "the hidden cells are one rectangle";
  // The high side of y hidden whole: a vertical form on y drops more.
  occ.hidden_height[1] = {0, 0, 0, 45, 45};
  const SliceChoice v = choose_slices(o, occ);
  EXPECT_EQ(v.indices.work_axis, 1);
  EXPECT_EQ(v.indices.y, 2) << "slices 0..2 stay";
  EXPECT_EQ(v.indices.z, 15);
  EXPECT_EQ(v.form, VisibleForm::vertical);
  EXPECT_EQ(v.dropped, m.triangles.size() - rendering_set(o.slices, v.indices).size());
  EXPECT_EQ(v.cell_dropped, v.dropped) << "on y the hidden cells are one rectangle too (the L on x is given up)";
  // Nothing hidden: nothing dropped, everything kept.
  occ.hidden_height[0].assign(nx, 0.0), occ.hidden_height[1].assign(ny, 0.0);
  const SliceChoice none = choose_slices(o, occ);
  EXPECT_EQ(none.dropped, 0u);
  EXPECT_EQ(rendering_set(o.slices, none.indices).size(), m.triangles.size());
}

TEST(Algorithm3, TheBestFormKeepsEveryTriangleItMust) {
  const MeshObject m = tower();
  const SliceWiseObject o = prepared_object(m);
  for (std::uint32_t seed = 1; seed <= 20; ++seed) {
    std::vector<char> keep(m.triangles.size(), 0);
    // Keep the triangles of a seeded corner of the tower (an L-shaped visible part and more).
    const double cx = 2.0 + seed % 7 * 2.5, cz = 3.0 + seed % 5 * 8.0;
    for (std::size_t t = 0; t < m.triangles.size(); ++t) {
      const Vec3 a = m.vertices[m.triangles[t][0]];
      keep[t] = (a.x > cx || a.z > cz) && (t * 2654435761u + seed) % 3 == 0;
    }
    const SliceChoice c = best_form_keeping(o, keep);
    const std::vector<std::uint32_t> drawn = rendering_set(o.slices, c.indices);
    for (std::size_t t = 0; t < keep.size(); ++t) {
      if (keep[t]) {
        ASSERT_TRUE(std::binary_search(drawn.begin(), drawn.end(), std::uint32_t(t))) << "seed " << seed << " triangle " << t;
      }
    }
    EXPECT_EQ(c.dropped, m.triangles.size() - drawn.size());
    EXPECT_GT(c.dropped, 0u) << "seed " << seed;
    EXPECT_GE(c.cell_dropped, c.dropped) << "seed " << seed;
  }
}

// With both vertical axes, the best pair of rectangles keeps every kept triangle, drops exactly
// what its indices drop, and never less than one axis: keeping the triangles that reach the
// tower's corner of low x and low y, or its top, (as if seen from the south-west over a wall)
// leaves an L in plan to drop.
TEST(Algorithm3, TheBestPairOfRectanglesKeepsEveryTriangleItMust) {
  const MeshObject m = tower();
  const SliceWiseObject o = prepared_object(m);
  std::size_t two_sided = 0;
  for (std::uint32_t seed = 1; seed <= 20; ++seed) {
    std::vector<char> keep(m.triangles.size(), 0);
    const double cx = 2.0 + seed % 7 * 2.5, cy = 1.0 + seed % 3 * 3.0, cz = 3.0 + seed % 5 * 8.0;
    for (std::size_t t = 0; t < m.triangles.size(); ++t) {
      Box3 b;
      for (std::uint32_t k : m.triangles[t]) b.extend(m.vertices[k]);
      keep[t] = ((b.lo.x < cx && b.lo.y < cy) || b.hi.z > cz) && (t * 2654435761u + seed) % 2 == 0;
    }
    const SliceChoice one = best_form_keeping(o, keep, false), both = best_form_keeping(o, keep, true);
    const std::vector<std::uint32_t> drawn = rendering_set(o.slices, both.indices);
    for (std::size_t t = 0; t < keep.size(); ++t)
      if (keep[t]) {
        ASSERT_TRUE(std::binary_search(drawn.begin(), drawn.end(), std::uint32_t(t))) << "seed " << seed << " triangle " << t;
      }
    EXPECT_EQ(both.dropped, m.triangles.size() - drawn.size()) << "seed " << seed;
    EXPECT_GE(both.dropped, one.dropped) << "seed " << seed;
    two_sided += both.form == VisibleForm::two_sided;
  }
  EXPECT_GT(two_sided, 10u) << "the corner cases must need both axes";
}

// The premise measure on known shapes: with every triangle reaching past x = 6 kept, the rest is
// the slices at the low-x end, one form; with only the two ends kept (x < 3 and x > 17), the
// middle is droppable per cell but no rectangle from a side reaches it.
TEST(Algorithm3, TheBestFormSaysWhenTheKeptTrianglesFitOneForm) {
  const MeshObject m = tower();
  const SliceWiseObject o = prepared_object(m);
  auto keep_where = [&](auto&& inside) {
    std::vector<char> keep(m.triangles.size(), 0);
    for (std::size_t t = 0; t < m.triangles.size(); ++t) {
      Box3 b;
      for (std::uint32_t v : m.triangles[t]) b.extend(m.vertices[v]);
      keep[t] = inside(b);
    }
    return best_form_keeping(o, keep);
  };
  const SliceChoice one = keep_where([](const Box3& b) { return b.hi.x > 6; });
  EXPECT_EQ(one.dropped, 588u);
  EXPECT_EQ(one.cell_dropped, 588u) << "a vertical form: the x < 6 slices";
  const SliceChoice two = keep_where([](const Box3& b) { return b.hi.x < 3 || b.lo.x > 17; });
  EXPECT_EQ(two.dropped, 78u);
  EXPECT_EQ(two.cell_dropped, 378u) << "the middle is droppable per cell, not by one form";
}

// A 20 x 14 x 45 m block as a closed mesh.
MeshObject plain_block() {
  Building b;
  b.id = 3;
  b.footprint = {{0, 0}, {20, 0}, {20, 14}, {0, 14}};
  b.height = 45;
  finish_building(b);
  return building_as_mesh(b);
}

TEST(VoxelErosion, APlainBlockShrinksByTheCubeOfVoxelsAndKeepsItsFoot) {
  const MeshObject m = plain_block();
  ASSERT_TRUE(m.closed);
  const double eps = 1.4142135623730951;
  const VoxelErosion e = erode_closed_mesh(m, {eps, eps, eps}, 0.5);
  ASSERT_EQ(e.boxes.size(), 1u);
  // On the grid: the wall voxels touch the walls, three more (1.5 m >= ε) eroded, the floor stays
  // on the ground (the kept voxels span [2, 18] x [2, 12] x [0, 43]). Pushed out to the boundary,
  // the box is the exact erosion by the cube: every wall and the roof recede by ε.
  EXPECT_EQ(e.kept, 32u * 20u * 86u);
  const Box3& b = e.boxes[0];
  for (auto [got, want] : {std::pair{b.lo.x, eps}, {b.lo.y, eps}, {b.hi.x, 20 - eps}, {b.hi.y, 14 - eps}, {b.hi.z, 45 - eps}})
    EXPECT_NEAR(got, want, 1e-8);
  EXPECT_EQ(b.lo.z, 0.0);
  EXPECT_EQ(e.ambiguous_columns, 0u);
}

// A 2 m view cell at eye height moves the eye by at most 1 m along x and along y, and not at all
// up or down: eroded by that square, the walls recede by 1 m and the roof stays (on the grid, the
// voxels touching a wall or the roof are lost too; pushing the box out gives them back).
TEST(VoxelErosion, APlainBlockErodedByASquareCellKeepsItsRoof) {
  const VoxelErosion e = erode_closed_mesh(plain_block(), {1, 1, 0}, 0.5);
  ASSERT_EQ(e.boxes.size(), 1u);
  EXPECT_EQ(e.kept, 34u * 22u * 89u) << "the voxels of [1.5, 18.5] x [1.5, 12.5] x [0, 44.5]";
  const Box3& b = e.boxes[0];
  for (auto [got, want] : {std::pair{b.lo.x, 1.0}, {b.lo.y, 1.0}, {b.hi.x, 19.0}, {b.hi.y, 13.0}, {b.hi.z, 45.0}})
    EXPECT_NEAR(got, want, 1e-8);
  EXPECT_EQ(b.lo.z, 0.0);
  EXPECT_THROW(erode_closed_mesh(plain_block(), {1, 1, -0.5}, 0.5), std::invalid_argument);
}

TEST(VoxelErosion, ADetailedBuildingsBoxesLieInsideItsBoxShrunkByEpsilon) {
  const MeshObject m = tower();
  ASSERT_TRUE(m.closed);
  const double eps = 1.4142135623730951;
  const VoxelErosion e = erode_closed_mesh(m, {eps, eps, eps}, 0.5);
  ASSERT_FALSE(e.boxes.empty());
  double volume = 0;
  for (const Box3& b : e.boxes) {
    EXPECT_GE(b.lo.x, m.bounds.lo.x + eps);
    EXPECT_LE(b.hi.x, m.bounds.hi.x - eps);
    EXPECT_GE(b.lo.y, m.bounds.lo.y + eps);
    EXPECT_LE(b.hi.y, m.bounds.hi.y - eps);
    EXPECT_GE(b.lo.z, m.bounds.lo.z);
    EXPECT_LE(b.hi.z, m.bounds.hi.z - eps);
    volume += (b.hi.x - b.lo.x) * (b.hi.y - b.lo.y) * (b.hi.z - b.lo.z);
  }
  EXPECT_GT(volume, 1000.0) << "the tower's core survives its window recesses";
  EXPECT_EQ(boxes_mesh(e.boxes).triangles.size(), 12 * e.boxes.size());
  EXPECT_THROW(erode_closed_mesh(m, {eps, eps, eps}, 0.5, 1000), std::invalid_argument);
}

// A podium [0, 10]^2 x [0, 6] with a tower [2, 8]^2 x [6, 20] standing on it: two closed boxes
// sharing no vertex, as the detailed generator and CityJSON parts make them.
MeshObject podium_and_tower() {
  const TriangleMesh t = boxes_mesh({{{0, 0, 0}, {10, 10, 6}}, {{2, 2, 6}, {8, 8, 20}}});
  MeshObject m;
  m.vertices = t.vertices, m.triangles = t.triangles;
  finish_mesh(m);
  return m;
}

bool in_some_box(const std::vector<Box3>& boxes, Vec3 p) {
  for (const Box3& b : boxes)
    if (b.lo.x <= p.x && p.x <= b.hi.x && b.lo.y <= p.y && p.y <= b.hi.y && b.lo.z <= p.z && p.z <= b.hi.z) return true;
  return false;
}

TEST(SolidParts, FindsTheFaceBetweenAPodiumAndItsTower) {
  const MeshObject m = podium_and_tower();
  ASSERT_TRUE(m.closed);
  const SolidParts parts = solid_parts(m);
  EXPECT_EQ(parts.parts, 2u);
  // The tower's floor lies on the podium's roof: interior. The roof is interior under the tower
  // only: partly, its boundary the ring around the tower.
  EXPECT_EQ(parts.interior_count, 2u);
  EXPECT_EQ(parts.partly_count, 2u);
  double ring = 0;
  for (const auto& [t, pieces] : parts.boundary_pieces) {
    EXPECT_EQ(parts.cover[t], SolidParts::partly);
    for (const auto& piece : pieces) {
      for (const Vec3& v : piece) EXPECT_DOUBLE_EQ(v.z, 6.0);
      for (std::size_t k = 0; k < piece.size(); ++k) {
        const Vec3 a = piece[k], b = piece[(k + 1) % piece.size()];
        ring += 0.5 * (a.x * b.y - a.y * b.x);
      }
    }
  }
  EXPECT_NEAR(ring, 100.0 - 36.0, 1e-9) << "the roof less the tower's floor";
}

TEST(VoxelErosion, ErodesThePodiumAndTowerAsOneSolid) {
  const MeshObject m = podium_and_tower();
  const double eps = 1.4142135623730951;
  const VoxelErosion e = erode_closed_mesh(m, {eps, eps, eps}, 0.5);
  EXPECT_EQ(e.solids, 2u);
  EXPECT_EQ(e.interior_triangles, 2u);
  EXPECT_EQ(e.partly_interior_triangles, 2u);
  EXPECT_EQ(e.ambiguous_columns, 0u) << "the roofs' diagonals pass through column centres: other lines decide";
  // Without the shared face taken as inside, the voxels touching it would be outside and erosion
  // would cut a slot from z = 4 to z = 8 through the building.
  for (double z : {3.9, 5.0, 6.0, 7.0, 8.1, 17.9}) EXPECT_TRUE(in_some_box(e.boxes, {5, 5, z})) << "z = " << z;
  EXPECT_FALSE(in_some_box(e.boxes, {5, 5, 18.7})) << "the tower's top, eroded by ε";
  EXPECT_TRUE(in_some_box(e.boxes, {5, 5, 18.5}));
  EXPECT_FALSE(in_some_box(e.boxes, {3.3, 5, 10})) << "the tower's wall, eroded by ε";
  EXPECT_TRUE(in_some_box(e.boxes, {3.5, 5, 10}));
  EXPECT_TRUE(in_some_box(e.boxes, {2.1, 5, 3.9})) << "the podium's core";
  // Conservative: every kept box, grown by ε, stays inside the podium or the tower (sampled).
  auto in_union = [](Vec3 p) {
    const bool podium = p.x >= 0 && p.x <= 10 && p.y >= 0 && p.y <= 10 && p.z <= 6;
    const bool tower = p.x >= 2 && p.x <= 8 && p.y >= 2 && p.y <= 8 && p.z >= 6 && p.z <= 20;
    return podium || tower;
  };
  for (const Box3& b : e.boxes)
    for (double x = b.lo.x - eps; x <= b.hi.x + eps + 1e-9; x += 0.25)
      for (double y = b.lo.y - eps; y <= b.hi.y + eps + 1e-9; y += 0.25)
        for (double z = std::max(b.lo.z - eps, 0.0); z <= b.hi.z + eps + 1e-9; z += 0.25) {
          const Vec3 p{x, y, z};
          if (length(p - Vec3{std::clamp(x, b.lo.x, b.hi.x), std::clamp(y, b.lo.y, b.hi.y), std::clamp(z, b.lo.z, b.hi.z)}) > eps) continue;
          ASSERT_TRUE(in_union(p)) << x << " " << y << " " << z;
        }
}

TEST(VoxelErosion, APodiumAndTowerErodedByASquareCellStayInsideWhenGrownByIt) {
  const VoxelErosion e = erode_closed_mesh(podium_and_tower(), {1, 1, 0}, 0.5);
  EXPECT_TRUE(in_some_box(e.boxes, {5, 5, 19.99})) << "the tower's top stays";
  EXPECT_FALSE(in_some_box(e.boxes, {2.9, 5, 10})) << "the tower's wall recedes by 1 m";
  EXPECT_TRUE(in_some_box(e.boxes, {3.1, 5, 10}));
  EXPECT_TRUE(in_some_box(e.boxes, {1.6, 5, 5.4})) << "the podium's rim under its roof";
  for (const Box3& b : e.boxes)
    for (double x = b.lo.x - 1; x <= b.hi.x + 1 + 1e-9; x += 0.25)
      for (double y = b.lo.y - 1; y <= b.hi.y + 1 + 1e-9; y += 0.25)
        for (double z = b.lo.z; z <= b.hi.z + 1e-9; z += 0.25) {
          const bool podium = x >= 0 && x <= 10 && y >= 0 && y <= 10 && z <= 6;
          const bool tower = x >= 2 && x <= 8 && y >= 2 && y <= 8 && z >= 6 && z <= 20;
          ASSERT_TRUE(podium || tower) << x << " " << y << " " << z;
        }
}

MeshObject box_object(ObjectId id, Box3 b) {
  const TriangleMesh t = boxes_mesh({b});
  MeshObject m;
  m.id = id, m.vertices = t.vertices, m.triangles = t.triangles;
  finish_mesh(m);
  return m;
}

// Row houses: A and B share the wall x = 10 (B taller, so A covers only its lower part); C meets B
// along an edge only; D stands apart.
TEST(SolidParts, TouchingPairsAreTheMeshesSharingAWallNotAnEdge) {
  const MeshObject a = box_object(1, {{0, 0, 0}, {10, 10, 8}}), b = box_object(2, {{10, 0, 0}, {20, 10, 12}});
  const MeshObject c = box_object(3, {{20, 10, 0}, {30, 20, 8}}), d = box_object(4, {{40, 0, 0}, {50, 10, 8}});
  using Pairs = std::vector<std::pair<std::uint32_t, std::uint32_t>>;
  EXPECT_EQ(touching_pairs({&a, &b, &c, &d}), (Pairs{{0, 1}}));
  EXPECT_EQ(touching_pairs({&d, &c, &b, &a}), (Pairs{{2, 3}}));
  EXPECT_EQ(touching_pairs({&a, &c, &d}), Pairs{});
}

TEST(VoxelErosion, TwoHousesSharingAPartyWallErodeWithoutASlot) {
  const MeshObject a = box_object(1, {{0, 0, 0}, {10, 10, 8}}), b = box_object(2, {{10, 0, 0}, {20, 10, 12}});
  const Vec3 cell{1, 1, 0};
  const VoxelErosion alone_a = erode_closed_mesh(a, cell, 0.5), alone_b = erode_closed_mesh(b, cell, 0.5);
  EXPECT_FALSE(in_some_box(alone_a.boxes, {9.1, 5, 4}) || in_some_box(alone_b.boxes, {10.9, 5, 4})) << "each recedes from the wall";
  const VoxelErosion joint = erode_closed_meshes({&a, &b}, cell, 0.5);
  ASSERT_EQ(joint.box_owner.size(), joint.boxes.size());
  EXPECT_EQ(joint.outward_of, (std::vector<std::uint8_t>{1, 1}));
  std::vector<Box3> own[2];
  for (std::size_t k = 0; k < joint.boxes.size(); ++k) own[joint.box_owner[k]].push_back(joint.boxes[k]);
  for (double x : {9.0, 9.99}) EXPECT_TRUE(in_some_box(own[0], {x, 5, 4})) << "x = " << x;
  for (double x : {10.01, 11.0}) EXPECT_TRUE(in_some_box(own[1], {x, 5, 4})) << "x = " << x;
  for (const Box3& k : own[0]) EXPECT_LE(k.hi.x, 10.0) << "A keeps what lies in A";
  for (const Box3& k : own[1]) EXPECT_GE(k.lo.x, 10.0);
  // Above A's roof, B's wall is outside again: it recedes by 1 m.
  EXPECT_FALSE(in_some_box(own[1], {10.9, 5, 10}));
  EXPECT_TRUE(in_some_box(own[1], {11.1, 5, 10}));
  // Conservative: every box grown by the cell stays inside A or B (sampled).
  for (const Box3& k : joint.boxes)
    for (double x = k.lo.x - 1; x <= k.hi.x + 1 + 1e-9; x += 0.25)
      for (double y = k.lo.y - 1; y <= k.hi.y + 1 + 1e-9; y += 0.25)
        for (double z = k.lo.z; z <= k.hi.z + 1e-9; z += 0.25) {
          const bool in_a = x >= 0 && x <= 10 && y >= 0 && y <= 10 && z <= 8;
          const bool in_b = x >= 10 && x <= 20 && y >= 0 && y <= 10 && z <= 12;
          ASSERT_TRUE(in_a || in_b) << x << " " << y << " " << z;
        }
}

// A building whose second part stands 0.3 m higher (sloping ground): below that part's floor is
// open space, not ground. The voxels its floor passes through are lost on the grid; pushed down,
// the part's box reaches its floor again, and no lower.
TEST(VoxelErosion, APartStandingHigherKeepsItsFloorAndNoMore) {
  const TriangleMesh t = boxes_mesh({{{0, 0, 0}, {10, 10, 8}}, {{20, 0, 0.3}, {30, 10, 8}}});
  MeshObject m;
  m.vertices = t.vertices, m.triangles = t.triangles;
  finish_mesh(m);
  const VoxelErosion e = erode_closed_mesh(m, {1, 1, 0}, 0.25);
  EXPECT_TRUE(in_some_box(e.boxes, {25, 5, 0.31}));
  EXPECT_FALSE(in_some_box(e.boxes, {25, 5, 0.29})) << "below the floor is open";
  EXPECT_TRUE(in_some_box(e.boxes, {5, 5, 0.0})) << "the lower part stands on the ground";
}

// A thin tower 20 m behind the party wall of two houses, seen from a cell in front of the wall:
// eroded one by one, the houses leave a 3 m slot the tower shows through; eroded as one, they hide it.
TEST(CellCulling, ATowerBehindAPartyWallIsHiddenWhenTheRowIsErodedAsOne) {
  Scene scene;
  scene.meshes = {box_object(1, {{0, 0, 0}, {10, 10, 8}}), box_object(2, {{10, 0, 0}, {20, 10, 8}}),
                  box_object(3, {{9.5, 30, 0}, {10.5, 32, 6}})};
  auto tower_visible = [&](bool jointly) {
    SliceSceneOptions so;
    so.shrinking = Shrinking::voxel_erosion;
    so.erode_touching = jointly;
    const SliceWiseScene prepared(scene, so);
    EXPECT_EQ(prepared.objects()[0].eroded_with, jointly ? 2u : 1u);
    EXPECT_EQ(prepared.objects()[2].eroded_with, 1u);
    CellCuller culler(prepared, CellCullingOptions{});
    const CellPvs pvs = culler.cull({10, -10, 1.7});
    bool seen = false;
    for (const ObjectVisibility& v : pvs.visible) seen = seen || v.object == 2;
    return seen;
  };
  EXPECT_TRUE(tower_visible(false)) << "through the slot between the houses";
  EXPECT_FALSE(tower_visible(true));
}

// The tower alone, seen from a 2 m cell in front of its south facade (y = 0): nothing else hides
// any of it, so only the object itself can.
ObjectVisibility tower_alone_from(Vec3 centre, bool self_occlusion, bool turned_away_faces, bool both_axes = false) {
  static const Scene scene = [] {
    Scene s;
    s.meshes.push_back(tower());
    return s;
  }();
  SliceSceneOptions so;
  so.shrinking = Shrinking::voxel_erosion;
  static const SliceWiseScene prepared(scene, so);
  CellCullingOptions co;
  co.self_occlusion = self_occlusion;
  co.turned_away_faces = turned_away_faces;
  co.both_vertical_axes = both_axes;
  CellCuller culler(prepared, co);
  const CellPvs pvs = culler.cull(centre);
  EXPECT_EQ(pvs.visible.size(), 1u);
  return pvs.visible.empty() ? ObjectVisibility{} : pvs.visible[0];
}

// 6 m from the facade the tower's box spans more than 80 degrees up: no zoomed view holds it, and
// the six cube faces take its queries. Its walls on the sides and at the back, its roof and floor
// turn away from the whole cell, so its far slices (along y, into the depth) hide behind it. Per
// triangle (each part of a slice bisected on its own, the best form over the triangles not shown
// hidden) one more slice drops than the rectangle of hidden cells gave (588 triangles, y 0 to 2).
TEST(CellCulling, ANearTowersFacesTurnedAwayFromTheCellHideItsFarSlices) {
  const Vec3 centre{10, -6, 1.7};
  const ObjectVisibility published = tower_alone_from(centre, false, false);
  const ObjectVisibility eroded_self = tower_alone_from(centre, true, false);
  const ObjectVisibility faces = tower_alone_from(centre, true, true);
  EXPECT_TRUE(faces.zoom_refused);
  EXPECT_EQ(published.choice.dropped, 0u) << "nothing but the tower itself could hide part of it";
  EXPECT_EQ(eroded_self.choice.dropped, 180u) << "its eroded solid alone: the far slices reach round to the side walls";
  EXPECT_EQ(faces.choice.dropped, 608u) << "of " << tower().triangles.size();
  EXPECT_EQ(faces.indices.work_axis, 1);
  EXPECT_EQ(faces.indices.y, 2) << "y slices 0 to 2 of 7 visible: the 6 m nearest the cell of the 14 m depth";
  EXPECT_EQ(faces.choice.form, VisibleForm::vertical);
}

// Seen across its south-west corner, the tower (1,504 triangles; 10 x 7 x 23 slices of 2 m) turns
// its north and east walls away from the cell. One vertical axis drops the lowest 12 m of the two
// eastmost x slices; both axes, in the same three bytes, drop the northmost y slice's too (the
// setbacks above keep faces turned to the cell in those slices higher up).
TEST(CellCulling, BothVerticalAxesDropBothFarWallsOfATowerSeenAcrossItsCorner) {
  const Vec3 centre{-12, -12, 1.7};
  const ObjectVisibility one = tower_alone_from(centre, true, true, false);
  const ObjectVisibility both = tower_alone_from(centre, true, true, true);
  EXPECT_NE(one.choice.form, VisibleForm::two_sided);
  EXPECT_EQ(one.indices.work_axis, 0);
  EXPECT_EQ(one.indices.x, 7);
  EXPECT_EQ(one.indices.z, 6);
  EXPECT_EQ(one.choice.dropped, 86u);
  EXPECT_EQ(both.choice.form, VisibleForm::two_sided);
  EXPECT_EQ(both.indices.work_axis, kBothVerticalAxes);
  EXPECT_EQ(both.indices.x, 7);
  EXPECT_EQ(both.indices.y, 5);
  EXPECT_EQ(both.indices.z, 6);
  EXPECT_EQ(both.choice.dropped, 164u);
  Scene scene;
  scene.meshes.push_back(tower());
  const SliceWiseScene prepared(scene, SliceSceneOptions{});
  EXPECT_EQ(both.choice.dropped, tower().triangles.size() - rendering_set(prepared.objects()[0].slices, both.indices).size());
}

TEST(Slicing, RefusesMoreSlicesThanAByteHolds) {
  SlicingOptions o;
  o.max_slices = 128;
  EXPECT_THROW(slice_object(tower(), o), std::invalid_argument);
}

}  // namespace
}  // namespace cullcheck::slice_wise
