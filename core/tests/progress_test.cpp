// Progress lines: their text (stage, how far, time left), and the switch that keeps them off.
#include "core/progress.hpp"

#include <gtest/gtest.h>

#include <cstdlib>

namespace cullcheck {
namespace {

TEST(Progress, SaysTheStageHowFarAndTheTimeLeft) {
  EXPECT_EQ(Progress::line("methods and the oracle along the path", 120, 300, "frames", 12.0),
            "methods and the oracle along the path: 120/300 frames (40%), 12 s, about 18 s left");
  EXPECT_EQ(Progress::line("VbAoI graph", 10, 1000, "nodes", 30.0), "VbAoI graph: 10/1000 nodes (1%), 30 s, about 50 min left");
  EXPECT_EQ(Progress::line("fuzzing", 500, 500, "cases", 7200.0), "fuzzing: 500/500 cases (100%), 2.0 h");
  EXPECT_EQ(Progress::line("search", 7, 0, "scenes", 3.0), "search: 7 scenes, 3 s") << "an unknown total";
}

TEST(Progress, QuietAndTheEnvironmentDecideWhetherLinesAreShown) {
  ::setenv("CULLCHECK_PROGRESS", "always", 1);
  Progress::set_mode(Progress::Mode::automatic);
  EXPECT_TRUE(Progress::shown());
  Progress::set_mode(Progress::Mode::never);  // --quiet wins over the environment
  EXPECT_FALSE(Progress::shown());
  ::setenv("CULLCHECK_PROGRESS", "never", 1);
  Progress::set_mode(Progress::Mode::always);
  EXPECT_FALSE(Progress::shown());
  ::unsetenv("CULLCHECK_PROGRESS");
  Progress::set_mode(Progress::Mode::automatic);
}

}  // namespace
}  // namespace cullcheck
