// The ε sweep's rows (reports/region_sweep.hpp) on a small seeded city: one row per method and
// radius, PVS reuse that adds up, and shrink_minkowski's occluder counts, which account for every
// building (the figures region_shrinking_test used to print).
#include "reports/region_sweep.hpp"

#include <gtest/gtest.h>

#include "generators/camera_paths.hpp"
#include "generators/city.hpp"

namespace cullcheck {
namespace {

TEST(RegionSweep, RowsPerMethodAndRadiusWithMinkowskiOccluderCounts) {
  const Scene scene = generators::make_city(
      "manhattan", 11, {{"blocks_x", 3}, {"blocks_y", 3}, {"buildings_per_block", 4}, {"thin_fraction", 0.3}});
  const CameraPath path = generators::make_camera_path("street_walk", scene, 1, {{"frames", 40}});
  const nlohmann::json rows =
      region_radius_sweep(scene, path, {"shrink_former", "shrink_minkowski"}, {0.5, 2.0}, 0.0, false, MethodOptions{});
  ASSERT_EQ(rows.size(), 4u);
  std::size_t minkowski_rows = 0;
  for (const nlohmann::json& row : rows) {
    SCOPED_TRACE(row.dump());
    const double radius = row.at("radius").get<double>();
    EXPECT_TRUE(radius == 0.5 || radius == 2.0);
    EXPECT_GE(row.at("pvs_computed").get<std::size_t>(), 1u);
    EXPECT_LE(row.at("pvs_computed").get<std::size_t>(), path.frames.size());
    EXPECT_DOUBLE_EQ(row.at("frames_per_pvs").get<double>() * row.at("pvs_computed").get<double>(), double(path.frames.size()));
    EXPECT_GE(row.at("pvs_mean").get<double>(), 1.0);
    if (row.at("method") != "shrink_minkowski") {
      EXPECT_FALSE(row.contains("minkowski_occluders"));
      continue;
    }
    ++minkowski_rows;
    const nlohmann::json& n = row.at("minkowski_occluders");
    const std::size_t total = n.at("occluders").get<std::size_t>() + n.at("faces_removed").get<std::size_t>() +
                              n.at("invalid_footprint").get<std::size_t>() + n.at("too_low").get<std::size_t>();
    EXPECT_EQ(total, scene.buildings.size());
    EXPECT_GT(n.at("occluders").get<std::size_t>(), 0u);
  }
  EXPECT_EQ(minkowski_rows, 2u);
}

}  // namespace
}  // namespace cullcheck
