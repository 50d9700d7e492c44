// The report page's sections, each a function of report.json (report_page.cpp puts them in
// order). Tables and text in page_tables.cpp, plots in page_plots.cpp.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "reports/html/report_page.hpp"

namespace cullcheck::html {

// object[key], or null when object is not an object or has no such key.
const nlohmann::json& member(const nlohmann::json& object, const char* key);
// A JSON number as a double, NaN when it is missing, null or not a number.
double value_of(const nlohmann::json& object, const char* key);
// A JSON string, or `fallback`.
std::string text_of(const nlohmann::json& object, const char* key, const std::string& fallback = "");
// A replay command in a copyable block (a button copies it; the text is selectable anyway).
std::string replay_block(const std::string& command);

// page_tables.cpp
std::string gate_section(const nlohmann::json& report);
std::string summary_section(const nlohmann::json& report);
std::string claims_section(const nlohmann::json& report);
std::string table_3_2_section(const nlohmann::json& report);
std::string table_4_1_section(const nlohmann::json& report);
// report.json's "online_culling" (cullcheck report --online-table): Table 1 in kind, the sweep, the long walk.
std::string online_culling_section(const nlohmann::json& report);
std::string radar_echo_section(const nlohmann::json& report);
std::string polar_diagram_section(const nlohmann::json& report);
std::string slice_wise_section(const nlohmann::json& report);
std::string regions_section(const nlohmann::json& report);
std::string vbaoi_table_section(const nlohmann::json& report);
// report.json's "speed_targets" (reports/speed_targets.hpp): issue 17's targets, before and after.
std::string speed_targets_section(const nlohmann::json& report);
std::string fuzz_section(const nlohmann::json& report);
std::string scene_section(const nlohmann::json& report);
std::string map_section(const nlohmann::json& report, const PageMap& map);

// page_plots.cpp
std::string pareto_section(const nlohmann::json& report);
std::string per_frame_section(const nlohmann::json& report);
std::string region_sweep_section(const nlohmann::json& report);
std::string vbaoi_plot_section(const nlohmann::json& report);
std::string scaling_section(const nlohmann::json& report);

}  // namespace cullcheck::html
