// The report page (issue 12): one self-contained HTML file made from report.json, readable
// offline (no network, no script library: plots are SVG written by svg_plot.hpp, the map a PNG
// inlined as base64). What it shows, top to bottom: the gate's verdict and the summary table; the
// claims ledger with each refuted claim's replay command (copyable); Pareto plots of culling time
// against over-estimation (and misdrawn pixels), with every swept knob; per-frame curves along
// the path; thesis Table 3.2 and Table 4.1 beside the thesis's values; the region methods; VbAoI
// messages against clients; the top-down map of the chosen frame; the scene, oracle and machine.
//
// The page is a pure function of the report and the map: the same inputs give the same bytes.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

namespace cullcheck::html {

struct PageMap {
  std::string png;      // the map's PNG bytes (frame_map.hpp), empty when there is none
  std::string problem;  // why there is no map (shown in its place)
};

// The page. Sections the report does not have are left out; a section whose data is malformed
// says so in place of its content (std::exception never escapes for a report cullcheck wrote).
std::string report_page(const nlohmann::json& report, const PageMap& map);

}  // namespace cullcheck::html
