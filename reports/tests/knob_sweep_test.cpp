// The knob sweep: its flag's parsing, the methods each knob reaches, and a sweep on a small city
// held to the main run's oracle (coarser horizons keep more, never fewer, of what was seen).
#include "reports/knob_sweep.hpp"

#include <gtest/gtest.h>

#include "core/errors.hpp"
#include "generators/camera_paths.hpp"
#include "generators/city.hpp"
#include "reports/statistics.hpp"

namespace cullcheck {
namespace {

TEST(KnobSweepFlag, ReadsAKnobAndItsValues) {
  const KnobSweep k = parse_knob_sweep("horizon_bins=256,1024,4096");
  EXPECT_EQ(k.knob, "horizon_bins");
  EXPECT_EQ(k.values, (std::vector<double>{256, 1024, 4096}));
  EXPECT_EQ(parse_knob_sweep("delta_radius=0.25").values, std::vector<double>{0.25});
}

TEST(KnobSweepFlag, RefusesWhatTheMethodsWouldRefuseAfterTheRun) {
  auto message = [](const std::string& text) {
    try {
      parse_knob_sweep(text);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message("bins=4").find("KNOB one of horizon_bins, quadtree_leaf_size, delta_radius"), std::string::npos);
  EXPECT_NE(message("horizon_bins=1000").find("not a power of two"), std::string::npos);
  EXPECT_NE(message("horizon_bins=2").find("not a power of two from 4"), std::string::npos);
  EXPECT_NE(message("quadtree_leaf_size=2.5").find("not a whole number"), std::string::npos);
  EXPECT_NE(message("delta_radius=0,1").find("'0' is not a positive number"), std::string::npos);
  EXPECT_NE(message("delta_radius=1,x").find("'x' is not a positive number"), std::string::npos);
  EXPECT_NE(message("delta_turn=2").find("above 1.5"), std::string::npos);
  EXPECT_NE(message("horizon_bins").find("is not KNOB=V1,V2"), std::string::npos);
}

TEST(KnobSweepFlag, EachKnobReachesTheMethodsThatReadIt) {
  EXPECT_EQ(methods_affected_by("delta_radius"), std::vector<std::string>{"delta_h_guarded"});
  const auto leaf = methods_affected_by("quadtree_leaf_size");
  EXPECT_NE(std::find(leaf.begin(), leaf.end(), "frustum"), leaf.end());
  const auto bins = methods_affected_by("horizon_bins");
  EXPECT_EQ(std::find(bins.begin(), bins.end(), "frustum"), bins.end()) << "frustum culling has no horizon";
  EXPECT_EQ(with_knob({}, "horizon_bins", 512).horizon_bins, 512u);
  EXPECT_DOUBLE_EQ(with_knob({}, "delta_turn", 0.2).delta_turn, 0.2);
}

TEST(KnobSweep, CoarserHorizonsKeepMoreAndMissNothingTheOracleSaw) {
  const SceneSource source{"default", 1, "{}", ""};
  const Scene scene = source.load();
  const CameraPath path = generators::make_camera_path("street_walk", scene, 3, {{"frames", 24}});
  VerificationOptions options;
  options.oracle_stride = 4;
  options.measure_bare_embree = false;
  const std::vector<std::string> methods = {"frustum", "oh_os_conservative"};
  const PathVerification main = verify_path(scene, source, path, methods, {}, options);
  ASSERT_EQ(main.checked_frames, (std::vector<std::size_t>{0, 4, 8, 12, 16, 20}));
  const nlohmann::json rows = knob_sweep(scene, path, methods, {}, {parse_knob_sweep("horizon_bins=256,4096")}, main);
  ASSERT_EQ(rows.size(), 2u) << "frustum culling is not swept by horizon_bins";
  EXPECT_EQ(rows[0]["method"], "oh_os_conservative");
  EXPECT_EQ(rows[0]["frames"], 24);
  EXPECT_FALSE(rows[0]["run_setting"].get<bool>());
  EXPECT_TRUE(rows[1]["run_setting"].get<bool>());
  EXPECT_GT(rows[0]["pvs_mean_checked_frames"].get<double>(), rows[1]["pvs_mean_checked_frames"].get<double>())
      << "256 bins over 360 degrees hide less than 4096";
  // At the run's own setting the sweep's PVS is the run's: the same over-estimation.
  const MethodRun& run = main.runs[1];
  EXPECT_DOUBLE_EQ(rows[1]["overestimation"].get<double>(),
                   mean(run.checked_pvs_size) / mean(run.witnessed_size));
  for (const auto& r : rows) EXPECT_EQ(r["misses"], 0) << r.dump();
}

}  // namespace
}  // namespace cullcheck
