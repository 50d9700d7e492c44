// The report page from hand-made reports: what a reader must find on it, escaped; sections the
// report lacks left out; a malformed section said in place, never losing the rest.
#include "reports/html/report_page.hpp"

#include <gtest/gtest.h>

namespace cullcheck::html {
namespace {

using nlohmann::json;

std::size_t occurrences(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

json small_report(bool passed) {
  json run = {{"method", "oh_os_conservative"}, {"frames", 3}, {"cull_ms_median", 0.25}, {"cull_ms_p95", 0.5},
              {"pvs_mean_checked_frames", 40.0}, {"witnessed_mean", 32.0}, {"overestimation", 1.25}, {"violations", passed ? 0 : 2},
              {"frames_with_violations", passed ? 0 : 1}, {"claims_conservative", true},
              {"per_frame", {{"frames", {0, 1, 2}}, {"cull_ms", {0.2, 0.25, 0.5}}, {"pvs", {39, 40, 41}},
                             {"checked_frames", {0, 2}}, {"witnessed", {31, 33}}}}};
  if (!passed)
    run["violation_replays"] = json::array({{{"frame", 2}, {"building", 17}, {"model", "ray_sampling_3d"}, {"witness", "ray <w>"},
                                             {"replay", "cullcheck verify --generator default --seed 1 --camera '{\"yaw\":1}'"}}});
  return {{"schema_version", 9},
          {"scene", {{"replay_flags", "--generator default --seed 1"}, {"building_count", 2808}}},
          {"path", {{"kind", "street_walk"}, {"frames", 3}}},
          {"runs", json::array({run})},
          {"gate", {{"passed", passed}, {"exit_code", passed ? 0 : 1}, {"conservative_violations", passed ? 0 : 2},
                    {"checks", json::array({{{"method", "oh_os_conservative"}, {"check", "conservative"},
                                             {"outcome", passed ? "passed" : "failed"}}})}}},
          {"claims", json::array({{{"id", "thesis-x"}, {"source", "thesis"}, {"statement", "A & B"}, {"holds", false},
                                   {"frames_checked", 10}, {"violations", 1},
                                   {"counterexample", {{"detail", "seen"}, {"replay", "cullcheck verify --params '{\"a\":1}'"}}}},
                                  {{"id", "ok-claim"}, {"holds", true}, {"frames_checked", 5}, {"violations", 0}}})},
          {"speedups", json::array({{{"faster", "delta_h_guarded"}, {"than", "oh_os_conservative"}, {"cull_ms_median_ratio", 3.1},
                                     {"thesis_table_3_2_culling_time", 9.18}}})}};
}

TEST(ReportPage, ShowsTheVerdictTheTableAndTheLedgerAtTheTop) {
  const std::string page = report_page(small_report(true), {});
  EXPECT_EQ(page.rfind("<!DOCTYPE html>", 0), 0u);
  EXPECT_NE(page.find("<b>PASSED</b> (exit code 0)"), std::string::npos);
  EXPECT_LT(page.find("id=\"gate\""), page.find("id=\"summary\""));
  EXPECT_LT(page.find("id=\"summary\""), page.find("id=\"claims\""));
  EXPECT_NE(page.find("<td class=\"name\">oh_os_conservative</td><td>3</td><td>0.250</td><td>0.500</td>"), std::string::npos);
  EXPECT_NE(page.find("2 claims checked, 1 refuted"), std::string::npos);
  EXPECT_NE(page.find("<span class=\"refuted\">REFUTED</span>"), std::string::npos);
  // The refuted claim's replay, escaped, in a copyable block; the holding claim has none.
  EXPECT_NE(page.find("<code>cullcheck verify --params &#39;{&quot;a&quot;:1}&#39;</code><button type=\"button\">copy</button>"),
            std::string::npos);
  EXPECT_EQ(occurrences(page, "<div class=\"replay\">"), 1u);
  EXPECT_NE(page.find("A &amp; B"), std::string::npos);
  EXPECT_NE(page.find("<td>3.10\u00d7</td>"), std::string::npos);
  EXPECT_NE(page.find("<td>9.18\u00d7</td>"), std::string::npos) << "Table 3.2 beside the thesis's value";
}

TEST(ReportPage, AFailedGateShowsItsViolationsWithTheirReplays) {
  const std::string page = report_page(small_report(false), {});
  EXPECT_NE(page.find("<div class=\"verdict failed\" id=\"gate-verdict\"><b>FAILED</b> (exit code 1): 2 objects seen but culled"),
            std::string::npos);
  EXPECT_NE(page.find("<span class=\"bad\">failed</span>"), std::string::npos);
  EXPECT_NE(page.find("frame 2, object 17 seen by ray_sampling_3d: ray &lt;w&gt;"), std::string::npos);
  EXPECT_EQ(occurrences(page, "<div class=\"replay\">"), 2u);
}

TEST(ReportPage, PlotsThePathAndTheTradeWhenTheReportHasThem) {
  const std::string page = report_page(small_report(true), {});
  for (const char* id : {"plot-pareto", "plot-frame-time", "plot-frame-pvs"})
    EXPECT_NE(page.find(std::string("id=\"") + id + "\""), std::string::npos) << id;
  EXPECT_NE(page.find("data-series=\"witnessed (oracle)\""), std::string::npos);
  // Sections the report does not have are left out, not drawn empty.
  for (const char* id : {"plot-vbaoi-messages", "plot-region-sweep", "id=\"table-4-1\"", "plot-scaling"})
    EXPECT_EQ(page.find(id), std::string::npos) << id;
}

// cullcheck report --online-table's section: Table 1's rows, the sweep and the long walk.
TEST(ReportPage, ShowsTheOnlineCullingTableWhenTheReportHasIt) {
  json report = small_report(true);
  EXPECT_EQ(report_page(report, {}).find("id=\"online-culling\""), std::string::npos);
  const json row = {{"method", "online_is"}, {"cull_ms_median", 0.102}, {"cull_ms_p95", 0.133}, {"critical_frames", 20},
                    {"critical_ms_median", 6.467}, {"polygons_sent_mean", 2667.0}, {"cr_v_mean", 0.843}, {"cr_o_mean", 0.976},
                    {"time_median_over_oh_os", 0.39}, {"error_frames", 0}, {"misdrawn_pixels", 0},
                    {"parameters", {{"shrink_pixels", 6}, {"mask_size", 256}}}, {"misdrawn_pixels_mean", 0.0}};
  report["online_culling"] = {{"table_1", json::array({{{"polygons", 108900}, {"rows", json::array({row})}}})},
                              {"delta_sweep", {{"rows", json::array({row})}}},
                              {"long_walk", {{"frames", 10000}, {"rows", json::array({{{"method", "online_is"}, {"error_frames", 193},
                                                                                        {"most_misdrawn_in_a_frame", 3385}}})}}}};
  const std::string page = report_page(report, {});
  EXPECT_NE(page.find("<td>108,900</td><td class=\"name\">online_is</td><td>0.102</td><td>0.133</td><td>20</td><td>6.47</td>"),
            std::string::npos);
  EXPECT_NE(page.find("Long walk, online_is: misdrawn pixels in 193 of 10,000 frames"), std::string::npos);
  EXPECT_NE(page.find("at most 3,385 in one"), std::string::npos);
}

// report.json's speed_targets: one row per target, the baseline's column only when a row has
// one, a missed goal and a violated precondition marked.
TEST(ReportPage, ShowsTheSpeedTargetsWhenTheReportHasThem) {
  json report = small_report(true);
  report["speed_targets"] = {{"rows", json::array()}};
  EXPECT_EQ(report_page(report, {}).find("id=\"speed-targets\""), std::string::npos);
  report["speed_targets"]["rows"] = {{{"id", "oracle_vs_bare_packets"}, {"goal", ">= 0.9"}, {"figure", 0.70}, {"met", false},
                                      {"from", "oracle: rays_per_second / bare_embree_packet_rays_per_second"}},
                                     {{"id", "adjustable_increase_thesis"}, {"goal", "<= 0.15, 0 violations"}, {"figure", nullptr}, {"met", false},
                                      {"from", "table_4_1 shrink_adjustable_thesis: violations"}}};
  std::string page = report_page(report, {});
  EXPECT_NE(page.find("<td class=\"name\">oracle_vs_bare_packets</td><td class=\"name\">&gt;= 0.9</td><td>0.700</td><td class=\"name\">"
                      "<span class=\"bad\">no</span></td>"),
            std::string::npos);
  EXPECT_NE(page.find("<span class=\"bad\">violations</span>"), std::string::npos);
  EXPECT_EQ(page.find("<th>before</th>"), std::string::npos);
  report["speed_targets"]["rows"][0]["before"] = 0.46;
  page = report_page(report, {});
  EXPECT_NE(page.find("<th>before</th>"), std::string::npos);
  EXPECT_NE(page.find("&gt;= 0.9</td><td>0.460</td><td>0.700</td>"), std::string::npos);
  EXPECT_NE(page.find("<td class=\"name\">adjustable_increase_thesis</td><td class=\"name\">&lt;= 0.15, 0 violations</td><td>\u2013</td>"),
            std::string::npos);  // no figure before for this row
}

// cullcheck report --radar-table's section: Table 3.3's rows with the thesis's time beside its
// 60-degree row, the echo pictures, the moving platform.
TEST(ReportPage, ShowsTheRadarEchoTableWhenTheReportHasIt) {
  json report = small_report(true);
  EXPECT_EQ(report_page(report, {}).find("id=\"radar-echo\""), std::string::npos);
  const json rule = {{"rule", "thesis"}, {"ms_median", 18.8}, {"ms_p95", 18.9}, {"visible", 8822}, {"triangles_tested", 47780},
                     {"missed", 6782}, {"pvs_over_witnessed", 0.731}};
  report["radar_echo"] = {{"height_m", 30}, {"thesis_ms_60deg", {{"100", 209}}},
                          {"terrains", json::array({{{"name", "generated"}, {"summary", "generated fractal terrain"}, {"triangles", 4959000},
                                                     {"oracle", json::array({{{"witnessed", 12076}}, {{"witnessed", 168512}}})},
                                                     {"rows", json::array({{{"grid", 100}, {"sector_deg", 60}, {"rules", json::array({rule})}}})},
                                                     {"echo_files", json::array({"/tmp/x/radar_echo_generated_thesis.png"})}}})},
                          {"moving_platform", {{"positions", 20}, {"step_m", 200}, {"ms_median", 300.5}, {"ms_p95", 320.0},
                                               {"previous_pvs_share_median", 0.9},
                                               {"regions", json::array({{{"radius_m", 100}, {"regions", 10}, {"rotations_per_region", 5},
                                                                         {"region_ms_median", 410.5}, {"speedup", 3.25},
                                                                         {"pvs_over_point_median", 1.75}, {"missed", 0}}})}}}};
  const std::string page = report_page(report, {});
  EXPECT_NE(page.find("<td>100\u00d7100</td><td>60</td><td class=\"name\">thesis</td><td>18.8</td><td>18.9</td><td>8,822</td><td>47,780</td>"),
            std::string::npos);
  EXPECT_NE(page.find("<td>209</td></tr>"), std::string::npos);
  EXPECT_NE(page.find("<img src=\"radar_echo_generated_thesis.png\""), std::string::npos);
  EXPECT_NE(page.find("Moving platform: 20 rotations"), std::string::npos);
  EXPECT_NE(page.find("PVS held 90.0% of each"), std::string::npos);
  EXPECT_NE(page.find("<tr><td>100</td><td>10</td><td>5.00</td><td>411</td><td>3.25</td><td>1.75</td><td>0</td></tr>"), std::string::npos)
      << page.substr(std::min(page.size(), page.find("Moving platform")), 900);
}

// cullcheck report --polar-table's section: construction per city, the walks with mismatches.
TEST(ReportPage, ShowsThePolarDiagramTableWhenTheReportHasIt) {
  json report = small_report(true);
  EXPECT_EQ(report_page(report, {}).find("id=\"polar-diagram\""), std::string::npos);
  report["polar_diagram"] = {
      {"cities", json::array({{{"scene", "star_block_city"}, {"buildings", 600}, {"vertices", 45000}, {"diagrams_ms", 66.9},
                               {"one_diagram_ms", 16.7}, {"fan_build_ms", 70.5}, {"cgal_build_ms", 520.2},
                               {"walks", json::array({{{"hfov_deg", 90}, {"frames_compared", 200}, {"fan_ms_median", 0.206},
                                                       {"fan_ms_p95", 0.661}, {"cgal_ms_median", 14.0}, {"cgal_over_fan_median", 68.0},
                                                       {"visible_mean", 14.9}, {"visible_edges_mean", 51.1}, {"rays_mean", 52.8},
                                                       {"rays_per_2k_median", 2.17}, {"mismatches", 1}}})}}})}};
  const std::string page = report_page(report, {});
  EXPECT_NE(page.find("<tr><td class=\"name\">star_block_city</td><td>600</td><td>45,000</td><td>66.9</td>"), std::string::npos);
  EXPECT_NE(page.find("<td>68.0</td>"), std::string::npos);
  EXPECT_NE(page.find("class=\"bad\""), std::string::npos) << "a mismatch shows as a violation";
}

// cullcheck report --slice-table's section: one row per city and occluder run, violations marked.
TEST(ReportPage, ShowsTheSliceWiseTableWhenTheReportHasIt) {
  json report = small_report(true);
  EXPECT_EQ(report_page(report, {}).find("id=\"slice-wise\""), std::string::npos);
  report["slice_wise"] = {
      {"cell_side_m", 2.0},
      {"replay", "cullcheck report --slice-table"},
      {"cities", json::array({{{"city", "detailed"},
                               {"table_1", {{"objects", 384}, {"triangles", 922320}}},
                               {"runs", json::array({{{"shrinking", "voxel_erosion"}, {"self_occlusion", true},
                                                      {"table_2", {{"cells", 14}, {"pvs_ms_per_cell_median", 237.3}, {"pvs_objects_median", 85}}},
                                                      {"table_3", {{"slice_wise_triangles_mean", 30905}, {"building_level_triangles_mean", 43739},
                                                                   {"slice_over_building", 0.707}}},
                                                      {"bound", {{"best_form_over_whole", 0.312}, {"witnessed_over_whole", 0.156}}},
                                                      {"oracle", {{"violations", 2}}}}})}}})}};
  const std::string page = report_page(report, {});
  EXPECT_NE(page.find("<tr><td class=\"name\">detailed</td><td class=\"name\">voxel_erosion + self</td><td>384</td><td>922,320</td>"),
            std::string::npos)
      << page.substr(std::min(page.size(), page.find("slice-wise")), 1500);
  EXPECT_NE(page.find("<td>70.7%</td>"), std::string::npos);
  EXPECT_NE(page.find("class=\"bad\""), std::string::npos) << "a violation shows";
}

TEST(ReportPage, CarriesTheMapInlineOrSaysWhyNot) {
  json report = small_report(true);
  report["map"] = {{"method", "oh_os_conservative"}, {"frame", 2}, {"chosen_by", "test"}, {"pvs", {1, 2}}, {"seen", {1}},
                   {"missed", json::array()}, {"overestimate", 1}};
  const std::string with = report_page(report, {std::string("\x89PNG", 4), ""});
  EXPECT_NE(with.find("<img id=\"map-image\" alt=\"top-down map of frame 2\" src=\"data:image/png;base64,iVBORw==\">"),
            std::string::npos);
  EXPECT_EQ(with.find("http://"), with.find("http://www.w3.org/2000/svg")) << "nothing is fetched from the network";
  EXPECT_EQ(with.find("https://"), std::string::npos);
  const std::string without = report_page(report, {"", "the scene file moved"});
  EXPECT_EQ(without.find("<img id=\"map-image\""), std::string::npos);
  EXPECT_NE(without.find("No map drawn: the scene file moved"), std::string::npos);
}

TEST(ReportPage, AMalformedSectionIsSaidInPlaceAndTheRestStays) {
  json report = small_report(true);
  report["claims"] = json::array({5});
  const std::string page = report_page(report, {});
  EXPECT_NE(page.find("<h2>Claims ledger</h2><p class=\"problem\">This section of the report could not be read"), std::string::npos);
  EXPECT_NE(page.find("<b>PASSED</b>"), std::string::npos);
  EXPECT_NE(page.find("id=\"plot-pareto\""), std::string::npos);
  EXPECT_NE(report_page(json::object(), {}).find("</html>"), std::string::npos) << "an empty report still gives a page";
}

}  // namespace
}  // namespace cullcheck::html
