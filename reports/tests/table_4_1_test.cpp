// Table 4.1 (reports/table_4_1.hpp) on a small plaza city: the disc's floors beside the rows.
// OH(OS)'s union over 61 eyes of each disc holds the centre's point PVS (the centre is one of the
// eyes) and grows when the frustum turns too (90 degrees adds eyes turned both ways); its values
// on this city are pinned.
#include "reports/table_4_1.hpp"

#include <gtest/gtest.h>

namespace cullcheck {
namespace {

TEST(Table41, OhOsUnionOverTheDiscIsTheFloorBesideTheOraclesUnion) {
  Table41Options o;
  o.params = {{"blocks_x", 12}, {"blocks_y", 12}, {"block_size", 40.0}, {"street_width", 10.0},
              {"buildings_per_block", 4}, {"plaza_blocks_x", 3}, {"plaza_blocks_y", 2}};
  o.region_methods = {"shrink_adjustable_corrected"};
  o.oracle_stride = 25;
  o.disc_stride = 2;
  const nlohmann::json t = table_4_1(o, MethodOptions{});
  const nlohmann::json& discs = t.at("disc_witnessed");
  ASSERT_EQ(discs.size(), 2u);
  for (const nlohmann::json& d : discs) {
    SCOPED_TRACE(d.dump());
    EXPECT_EQ(d.at("oh_os_union_eyes").get<std::size_t>(), 61u);
    EXPECT_GE(d.at("oh_os_union_mean").get<double>(), d.at("point_pvs_mean").get<double>());
    EXPECT_GT(d.at("frames").get<std::size_t>(), 3u);
  }
  EXPECT_EQ(discs[0].at("viewing_angle").get<int>(), 60);
  EXPECT_GE(discs[1].at("oh_os_union_mean").get<double>(), discs[0].at("oh_os_union_mean").get<double>());
  // 7 checked frames: 155 point-PVS members, 174 in OH(OS)'s unions at 60 degrees, 232 at 90.
  EXPECT_EQ(discs[0].at("frames").get<std::size_t>(), 7u);
  EXPECT_DOUBLE_EQ(discs[0].at("point_pvs_mean").get<double>(), 155.0 / 7);
  EXPECT_DOUBLE_EQ(discs[0].at("oh_os_union_mean").get<double>(), 174.0 / 7);
  EXPECT_DOUBLE_EQ(discs[1].at("oh_os_union_mean").get<double>(), 232.0 / 7);
}

}  // namespace
}  // namespace cullcheck
