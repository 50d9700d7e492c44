// Detailed building meshes (generators/detailed_buildings.hpp): every mesh closed and inside its
// building's box, triangle counts in the slice-wise paper's range, a city of millions of
// triangles from the default layout.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/elapsed.hpp"
#include "generators/city.hpp"
#include "generators/detailed_buildings.hpp"

namespace cullcheck::generators {
namespace {

DetailedCityParams small_city() {
  DetailedCityParams p;
  p.layout.blocks_x = 4, p.layout.blocks_y = 3, p.layout.buildings_per_block = 4;
  p.layout.tower_fraction = 0.3, p.layout.thin_fraction = 0.2;
  p.arcade_fraction = 0.4;
  return p;
}

TEST(DetailedBuildings, EveryMeshIsClosedAndInsideItsBuilding) {
  const DetailedCityParams p = small_city();
  const Scene layout = manhattan_city(p.layout, 3);
  const Scene city = detailed_city(p, 3);
  ASSERT_EQ(city.meshes.size(), layout.buildings.size());
  EXPECT_TRUE(city.buildings.empty());
  for (std::size_t i = 0; i < city.meshes.size(); ++i) {
    MeshObject m = city.meshes[i];
    const Box3 claimed = m.bounds;
    finish_mesh(m);
    EXPECT_TRUE(m.closed) << "building " << m.id;
    EXPECT_EQ(m.id, layout.buildings[i].id);
    const Box3& b = layout.buildings[i].bounds;
    EXPECT_GE(m.bounds.lo.x, b.lo.x - 1e-9);
    EXPECT_LE(m.bounds.hi.x, b.hi.x + 1e-9);
    EXPECT_GE(m.bounds.lo.y, b.lo.y - 1e-9);
    EXPECT_LE(m.bounds.hi.y, b.hi.y + 1e-9);
    EXPECT_NEAR(m.bounds.lo.z, 0.0, 1e-9);
    EXPECT_NEAR(m.bounds.hi.z, b.hi.z, 1e-9) << "the mesh reaches the building's height";
    EXPECT_EQ(claimed.lo.x, m.bounds.lo.x);
    EXPECT_EQ(claimed.hi.z, m.bounds.hi.z);
    EXPECT_LE(m.triangles.size(), static_cast<std::size_t>(p.max_triangles));
  }
}

// The paper's buildings hold 60 to 30,768 faces (Vienna) and 5,000 to 8,000 (its generated
// city); ours span tens (blank walls) to 10,000, set by storeys and bays.
TEST(DetailedBuildings, TriangleCountsSpanHundredsToThousands) {
  DetailedCityParams p = small_city();
  p.layout.max_height = 60;
  const Scene city = detailed_city(p, 11);
  std::vector<std::size_t> counts;
  for (const MeshObject& m : city.meshes) counts.push_back(m.triangles.size());
  std::sort(counts.begin(), counts.end());
  std::printf("triangles per building: min %zu, median %zu, max %zu over %zu buildings\n", counts.front(), counts[counts.size() / 2],
              counts.back(), counts.size());
  EXPECT_LE(counts.front(), 200u);
  EXPECT_GE(counts.front(), 20u);
  EXPECT_GE(counts.back(), 4000u);
  EXPECT_LE(counts.back(), 10000u);
}

TEST(DetailedBuildings, TheDefaultLayoutMakesACityOfMillionsOfTriangles) {
  DetailedCityParams p;
  p.layout = default_city_params();
  const auto start = std::chrono::steady_clock::now();
  const Scene city = detailed_city(p, 1);
  const double seconds = seconds_since(start);
  std::size_t triangles = 0;
  for (const MeshObject& m : city.meshes) triangles += m.triangles.size();
  std::printf("detailed default city: %zu buildings, %zu triangles in %.2f s\n", city.meshes.size(), triangles, seconds);
  EXPECT_EQ(city.meshes.size(), 2808u);
  EXPECT_GE(triangles, 2'000'000u);
}

TEST(DetailedBuildings, ByNameWithItsParameters) {
  const Scene s = make_city("detailed", 2, nlohmann::json{{"blocks_x", 2}, {"blocks_y", 2}, {"bay_width", 5.0}});
  EXPECT_EQ(s.provenance.generator, "detailed");
  EXPECT_FALSE(s.meshes.empty());
  EXPECT_THROW(make_city("detailed", 2, nlohmann::json{{"window_share", 0.95}}), std::exception);
}

}  // namespace
}  // namespace cullcheck::generators
