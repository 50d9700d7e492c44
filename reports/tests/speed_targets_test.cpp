// Issue 17's targets read off hand-made reports: each row's figure from the right fields, met or
// not against its goal, the baseline's figure as "before", no row for a section the report lacks,
// and the section left out of timing-free comparisons.
#include "reports/speed_targets.hpp"

#include <gtest/gtest.h>

#include "reports/report.hpp"

namespace cullcheck {
namespace {

using nlohmann::json;

json scaling_row(double buildings, double oh_median, double oh_p95, double dh_median, double dh_p95, int differs) {
  return {{"buildings", buildings},
          {"methods",
           {{{"method", "oh_os_conservative"}, {"cull_ms_median", oh_median}, {"cull_ms_p95", oh_p95}, {"frames_pvs_differs_from_oh_os", 0}},
            {{"method", "delta_h_guarded"}, {"cull_ms_median", dh_median}, {"cull_ms_p95", dh_p95}, {"frames_pvs_differs_from_oh_os", differs}}}}};
}

json a_report() {
  json r;
  // The row nearest 160,000 buildings is read (not the largest, not the first).
  r["scaling"] = {scaling_row(10000, 1.0, 1.0, 1.0, 1.0, 7), scaling_row(160000, 0.8, 1.6, 0.2, 0.8, 0),
                  scaling_row(640000, 2.0, 2.0, 0.1, 0.1, 9)};
  r["table_4_1"]["rows"] = {
      {{"method", "shrink_adjustable_thesis"}, {"viewing_angle", 60}, {"increase_over_method_1_at_60", 0.24}, {"violations", 3}},
      {{"method", "shrink_adjustable_corrected"}, {"viewing_angle", 60}, {"increase_over_method_1_at_60", 0.12}, {"violations", 0}},
      {{"method", "shrink_adjustable_corrected"}, {"viewing_angle", 90}, {"increase_over_method_1_at_60", 0.01}, {"violations", 0}}};
  r["oracle"] = {{"rays_per_second", 27e6}, {"bare_embree_packet_rays_per_second", 30e6}};
  // OH(OS)'s row, not the first method's (whose bound is null: it sweeps no quadtree).
  r["runs"] = {{{"method", "frustum"}, {"tests_over_exact_traversal", nullptr}},
               {{"method", "oh_os_thesis"}, {"tests_over_exact_traversal", 1.1}},
               {{"method", "oh_os_conservative"}, {"tests_over_exact_traversal", 1.25}}};
  r["vbaoi"]["graph"] = {{"build_seconds", 57.0}, {"buildings", 10086}};
  r["vbaoi"]["runs"] = {{{"clients", 100}, {"policies", {{{"policy", "vbaoi"}, {"deliveries_vs_limit", 1.5}, {"missed_updates", 0}}}}},
                        {{"clients", 1000},
                         {"policies",
                          {{{"policy", "broadcast"}, {"deliveries_vs_limit", 57.5}, {"missed_updates", 0}},
                           {{"policy", "vbaoi"}, {"deliveries_vs_limit", 5.0}, {"missed_updates", 2}},
                           {{"policy", "vbaoi_filtered"}, {"deliveries_vs_limit", 1.25}, {"missed_updates", 0}}}}}};
  return r;
}

const json& row(const json& targets, const std::string& id) {
  for (const json& r : targets["rows"])
    if (r["id"] == id) return r;
  static const json none;
  ADD_FAILURE() << "no row " << id;
  return none;
}

TEST(SpeedTargets, EachRowReadsItsFieldsAndSaysWhetherItsGoalIsMet) {
  const json t = speed_targets(a_report());
  ASSERT_EQ(t["rows"].size(), 12u);  // no row for shrink_adjustable_conservative: the table has none
  EXPECT_DOUBLE_EQ(row(t, "delta_h_guarded_median_speedup")["figure"].get<double>(), 4.0);  // 0.8 / 0.2
  EXPECT_FALSE(row(t, "delta_h_guarded_median_speedup")["met"].get<bool>());
  EXPECT_DOUBLE_EQ(row(t, "delta_h_guarded_p95_speedup")["figure"].get<double>(), 2.0);  // 1.6 / 0.8
  EXPECT_EQ(row(t, "delta_h_guarded_pvs_differs")["figure"].get<double>(), 0.0);
  EXPECT_TRUE(row(t, "delta_h_guarded_pvs_differs")["met"].get<bool>());
  EXPECT_EQ(row(t, "delta_h_guarded_median_speedup")["from"].get<std::string>(),
            "scaling (160000 buildings): oh_os_conservative cull_ms_median / delta_h_guarded cull_ms_median");
  // Violations make the row fail whatever the increase.
  EXPECT_TRUE(row(t, "adjustable_increase_thesis")["figure"].is_null());
  EXPECT_FALSE(row(t, "adjustable_increase_thesis")["met"].get<bool>());
  EXPECT_DOUBLE_EQ(row(t, "adjustable_increase_corrected")["figure"].get<double>(), 0.12);  // the 60-degree row
  EXPECT_TRUE(row(t, "adjustable_increase_corrected")["met"].get<bool>());
  EXPECT_DOUBLE_EQ(row(t, "oh_os_tests_over_exact_traversal")["figure"].get<double>(), 1.25);
  EXPECT_FALSE(row(t, "oh_os_tests_over_exact_traversal")["met"].get<bool>());  // goal 1.18
  EXPECT_DOUBLE_EQ(row(t, "oracle_vs_bare_packets")["figure"].get<double>(), 0.9);
  EXPECT_TRUE(row(t, "oracle_vs_bare_packets")["met"].get<bool>());
  EXPECT_FALSE(row(t, "vbaoi_graph_seconds")["met"].get<bool>());
  // The run with the most clients, its vbaoi policy (not broadcast, not the 100-client run).
  EXPECT_DOUBLE_EQ(row(t, "vbaoi_deliveries_vs_limit")["figure"].get<double>(), 5.0);
  EXPECT_EQ(row(t, "vbaoi_missed_updates")["figure"].get<double>(), 2.0);
  EXPECT_FALSE(row(t, "vbaoi_missed_updates")["met"].get<bool>());
  // The same two figures of the policy with the server's sight filter.
  EXPECT_DOUBLE_EQ(row(t, "vbaoi_filtered_deliveries_vs_limit")["figure"].get<double>(), 1.25);
  EXPECT_TRUE(row(t, "vbaoi_filtered_deliveries_vs_limit")["met"].get<bool>());
  EXPECT_EQ(row(t, "vbaoi_filtered_missed_updates")["from"].get<std::string>(),
            "vbaoi run of 1000 clients, policy vbaoi_filtered: missed_updates");
  EXPECT_TRUE(row(t, "vbaoi_filtered_missed_updates")["met"].get<bool>());
  EXPECT_FALSE(t["rows"][0].contains("before"));
}

TEST(SpeedTargets, ABaselineGivesItsFiguresAsBeforeWhereItHasThem) {
  json old;
  old["oracle"] = {{"rays_per_second", 15e6}, {"bare_embree_packet_rays_per_second", 30e6}};
  const json t = speed_targets(a_report(), &old);
  EXPECT_DOUBLE_EQ(row(t, "oracle_vs_bare_packets")["before"].get<double>(), 0.5);
  EXPECT_FALSE(row(t, "vbaoi_graph_seconds").contains("before"));  // the baseline ran no VbAoI
  const std::string text = speed_targets_text(t);
  EXPECT_NE(text.find("oracle_vs_bare_packets               >= 0.9                            0.5        0.9  yes"), std::string::npos) << text;
}

TEST(SpeedTargets, AReportWithoutTheSectionsHasNoRowsAndComparisonsLeaveTheSectionOut) {
  EXPECT_TRUE(speed_targets(json::object())["rows"].empty());
  json r = a_report();
  r["speed_targets"] = speed_targets(r);
  EXPECT_FALSE(without_timings(r).contains("speed_targets"));
}

}  // namespace
}  // namespace cullcheck
