// The city-size rows (reports/scaling.hpp) on two small thesis-layout cities: one row per size in
// order, the guarded ΔH's PVS identical to OH(OS)'s at every frame, and the memory high-water
// mark present and never falling from one size to the next (issue 17 asks for memory peaks).
#include "reports/scaling.hpp"

#include <gtest/gtest.h>

namespace cullcheck {
namespace {

TEST(Scaling, RowsPerSizeWithPeakMemoryAndDeltaHAsOhOs) {
  ScalingOptions o;
  o.grids = {10, 20};
  o.frames = 30;
  o.methods = {"oh_os_conservative", "delta_h_guarded"};
  const nlohmann::json rows = run_scaling(o);
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[0].at("buildings").get<std::size_t>(), 100u);
  EXPECT_EQ(rows[1].at("buildings").get<std::size_t>(), 400u);
  std::uint64_t previous = 0;
  for (const nlohmann::json& row : rows) {
    SCOPED_TRACE(row.dump());
    EXPECT_EQ(row.at("frames").get<std::size_t>(), 30u);
    const std::uint64_t peak = row.at("peak_rss_bytes").get<std::uint64_t>();
    EXPECT_GT(peak, std::uint64_t{1} << 20);  // a running test binary holds more than 1 MiB
    EXPECT_GE(peak, previous);
    previous = peak;
    ASSERT_EQ(row.at("methods").size(), 2u);
    for (const nlohmann::json& m : row.at("methods")) EXPECT_EQ(m.at("frames_pvs_differs_from_oh_os").get<std::size_t>(), 0u);
  }
  EXPECT_NE(scaling_table(rows).find("peak resident memory"), std::string::npos);
}

}  // namespace
}  // namespace cullcheck
