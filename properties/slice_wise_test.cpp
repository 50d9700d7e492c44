// The slice-wise structure (engine/slice_wise/slicing.hpp, Yılmaz & Güdükbay sections 3.2-3.3):
// every triangle in at least one slice on each axis and exactly in the slabs its extent meets;
// the three signed indices of Fig. 5 select the slices they say; the rendering set of "all
// visible" is the whole object and of an L-shape the union of its two parts.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "engine/slice_wise/slicing.hpp"
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
  // 20 x 14 x 45 m at 3 m slabs: 7, 5 and 15 slices.
  EXPECT_EQ(s.axes[0].count(), 7u);
  EXPECT_EQ(s.axes[1].count(), 5u);
  EXPECT_EQ(s.axes[2].count(), 15u);
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

TEST(Slicing, RefusesMoreSlicesThanAByteHolds) {
  SlicingOptions o;
  o.max_slices = 128;
  EXPECT_THROW(slice_object(tower(), o), std::invalid_argument);
}

}  // namespace
}  // namespace cullcheck::slice_wise
