// The ray oracle's merged mesh at the edge of Embree's 32-bit indices (oracle/mesh.hpp): three
// unshared vertices per triangle, so 1,431,655,765 triangles are the most it can index; one more
// is an InputError naming the scene's triangles, never indices that wrap around 2^32.
#include <gtest/gtest.h>

#include <limits>

#include "core/errors.hpp"
#include "oracle/mesh.hpp"
#include "test_scenes.hpp"

namespace cullcheck::oracle {
namespace {

TEST(MergedMeshLimits, TheLastIndexOfTheLargestMeshFitsIn32Bits) {
  EXPECT_EQ(kMaxMergedTriangles, 1431655765u);
  EXPECT_LE(3 * kMaxMergedTriangles - 1, std::size_t{std::numeric_limits<std::uint32_t>::max()});
  EXPECT_GT(3 * (kMaxMergedTriangles + 1) - 1, std::size_t{std::numeric_limits<std::uint32_t>::max()});
}

TEST(MergedMeshLimits, OneTriangleMoreIsAnInputErrorNamingTheTriangles) {
  EXPECT_NO_THROW(check_merged_triangle_count(0));
  EXPECT_NO_THROW(check_merged_triangle_count(1431655765));
  try {
    check_merged_triangle_count(1431655766);
    FAIL() << "1,431,655,766 triangles were accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.object(), "scene");
    EXPECT_EQ(e.field(), "triangles");
    EXPECT_NE(e.problem().find("1431655766"), std::string::npos) << e.what();
  }
}

TEST(MergedMeshLimits, TriangulateIndexesEveryVertexOnce) {
  // Two objects: indices continue across them (the offsets the limit protects).
  const TriangleMesh mesh = triangulate(testing::scene_of({box_building(1, 0, 0, 2, 2, 3), box_building(2, 5, 0, 7, 2, 3)}));
  ASSERT_EQ(mesh.triangles.size(), 20u);
  ASSERT_EQ(mesh.vertices.size(), 60u);
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t)
    EXPECT_EQ(mesh.triangles[t], (std::array<std::uint32_t, 3>{std::uint32_t(3 * t), std::uint32_t(3 * t + 1), std::uint32_t(3 * t + 2)}));
}

}  // namespace
}  // namespace cullcheck::oracle
