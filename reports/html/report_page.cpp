#include "reports/html/report_page.hpp"

#include <cmath>
#include <functional>

#include "reports/html/html_text.hpp"
#include "reports/html/page_sections.hpp"

namespace cullcheck::html {
namespace {

constexpr const char* kStyle = R"CSS(
body { font: 14px/1.45 system-ui, -apple-system, "Segoe UI", sans-serif; margin: 0 auto; max-width: 1180px; padding: 0 20px 60px; color: #1d1d1f; }
h1 { font-size: 24px; margin: 22px 0 4px; } h2 { font-size: 19px; margin: 34px 0 8px; border-bottom: 1px solid #ddd; padding-bottom: 4px; }
h3 { font-size: 15px; margin: 18px 0 6px; }
table { border-collapse: collapse; margin: 8px 0 14px; font-variant-numeric: tabular-nums; }
th, td { border-bottom: 1px solid #e4e4e4; padding: 3px 9px; text-align: right; vertical-align: top; }
th { background: #f4f4f6; font-weight: 600; } td.name, th.name { text-align: left; }
.verdict { padding: 12px 16px; border-radius: 6px; font-size: 16px; margin: 12px 0; }
.verdict.passed { background: #e3f4e6; border: 1px solid #7bc48a; } .verdict.failed { background: #fde4e1; border: 1px solid #e0786a; }
.holds { color: #17742b; font-weight: 600; } .refuted { color: #b3261e; font-weight: 600; } .bad { color: #b3261e; font-weight: 600; }
.replay { display: flex; gap: 6px; align-items: flex-start; margin: 4px 0; }
.replay code { display: block; white-space: pre-wrap; word-break: break-all; background: #f6f6f8; border: 1px solid #e2e2e6; padding: 4px 6px; font-size: 12px; flex: 1; }
.replay button { font-size: 12px; padding: 3px 8px; cursor: pointer; }
figure.plot-figure { margin: 10px 0 18px; } svg.plot { max-width: 100%; height: auto; font-size: 12px; }
svg.plot .grid { stroke: #eee; } svg.plot .frame { fill: none; stroke: #999; } svg.plot .title { font-weight: 600; font-size: 13px; }
svg.plot .tick { fill: #555; font-size: 11px; } svg.plot .empty { fill: #888; } svg.plot .legend text { font-size: 11.5px; }
.plot-note, .note { color: #555; font-size: 12.5px; margin: 2px 0 10px; }
.map img { max-width: 100%; border: 1px solid #ccc; image-rendering: pixelated; }
.swatch { display: inline-block; width: 12px; height: 12px; border: 1px solid #555; vertical-align: -2px; margin: 0 4px 0 12px; }
nav a { margin-right: 12px; } .problem { color: #b3261e; }
)CSS";

// Records script errors before anything else runs, then says on <body> what rendered, so a test
// in a headless browser can read the verdict from the DOM (data-script-errors, data-plots, data-map).
constexpr const char* kErrorHook = R"JS(
window.cullcheckErrors = [];
window.addEventListener('error', function (e) { window.cullcheckErrors.push(String(e.message)); });
)JS";

constexpr const char* kScript = R"JS(
(function () {
  document.querySelectorAll('.replay button').forEach(function (button) {
    button.addEventListener('click', function () {
      var text = button.parentElement.querySelector('code').textContent;
      var done = function () { button.textContent = 'copied'; setTimeout(function () { button.textContent = 'copy'; }, 1200); };
      if (navigator.clipboard && window.isSecureContext) { navigator.clipboard.writeText(text).then(done); return; }
      var area = document.createElement('textarea'); area.value = text; document.body.appendChild(area); area.select();
      try { document.execCommand('copy'); done(); } finally { document.body.removeChild(area); }
    });
  });
  var body = document.body;
  var plots = document.querySelectorAll('svg.plot');
  var drawn = 0;
  plots.forEach(function (svg) { if (Number(svg.getAttribute('data-points')) > 0 && svg.getBBox().width > 0) drawn += 1; });
  body.setAttribute('data-plots', String(plots.length));
  body.setAttribute('data-plots-with-data', String(drawn));
  var map = document.getElementById('map-image');
  var mark = function () {
    body.setAttribute('data-map', map && map.complete && map.naturalWidth > 0 ? 'drawn' : 'none');
    body.setAttribute('data-script-errors', String(window.cullcheckErrors.length));
    if (window.cullcheckErrors.length) body.setAttribute('data-script-error-text', window.cullcheckErrors.join(' | '));
    body.setAttribute('data-rendered', 'yes');
  };
  if (map && !map.complete) { map.addEventListener('load', mark); map.addEventListener('error', mark); } else { mark(); }
})();
)JS";

// A section, or a note saying why it could not be drawn: a malformed section never loses the rest.
std::string guarded(const char* name, const std::function<std::string()>& section) {
  try {
    return section();
  } catch (const std::exception& e) {
    return "<section><h2>" + escape(name) + "</h2><p class=\"problem\">This section of the report could not be read: " +
           escape(e.what()) + "</p></section>\n";
  }
}

}  // namespace

const nlohmann::json& member(const nlohmann::json& object, const char* key) {
  static const nlohmann::json null;
  if (!object.is_object()) return null;
  const auto it = object.find(key);
  return it == object.end() ? null : *it;
}

double value_of(const nlohmann::json& object, const char* key) {
  if (!object.is_object()) return NAN;
  const auto it = object.find(key);
  return it != object.end() && it->is_number() ? it->get<double>() : NAN;
}

std::string text_of(const nlohmann::json& object, const char* key, const std::string& fallback) {
  if (!object.is_object()) return fallback;
  const auto it = object.find(key);
  return it != object.end() && it->is_string() ? it->get<std::string>() : fallback;
}

std::string replay_block(const std::string& command) {
  return "<div class=\"replay\"><code>" + escape(command) + "</code><button type=\"button\">copy</button></div>\n";
}

std::string report_page(const nlohmann::json& report, const PageMap& map) {
  const nlohmann::json& scene = report.is_object() && report.contains("scene") ? report["scene"] : nlohmann::json::object();
  const std::string title = "cullcheck report: " + text_of(scene, "replay_flags", "scene");
  std::string page = "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>" + escape(title) +
                     "</title>\n<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n<style>" + kStyle +
                     "</style>\n<script>" + kErrorHook + "</script>\n</head>\n<body>\n";
  page += "<h1>cullcheck report</h1>\n<p class=\"note\">Scene <code>" + escape(text_of(scene, "replay_flags")) + "</code>";
  if (report.contains("path") && report["path"].is_object())
    page += ", path " + escape(text_of(report["path"], "kind")) + " of " + count(value_of(report["path"], "frames")) + " frames";
  page += ". Schema version " + escape(count(value_of(report, "schema_version"))) + ".</p>\n";
  page += "<nav><a href=\"#gate\">Gate</a><a href=\"#summary\">Methods</a><a href=\"#claims\">Claims</a><a href=\"#pareto\">Speed "
          "and accuracy</a><a href=\"#per-frame\">Per frame</a><a href=\"#tables\">Thesis tables</a><a href=\"#online-culling\">On-line culling</a><a href=\"#radar-echo\">Radar</a><a href=\"#polar-diagram\">Polar diagrams</a><a href=\"#slice-wise\">Slice-wise</a><a href=\"#regions\">Regions</a>"
          "<a href=\"#vbaoi\">VbAoI</a><a href=\"#speed-targets\">Speed targets</a><a href=\"#map\">Map</a><a href=\"#scene\">Scene</a></nav>\n";
  page += guarded("Gate", [&] { return gate_section(report); });
  page += guarded("Methods", [&] { return summary_section(report); });
  page += guarded("Claims ledger", [&] { return claims_section(report); });
  page += guarded("Speed against accuracy", [&] { return pareto_section(report); });
  page += guarded("Along the path", [&] { return per_frame_section(report); });
  page += "<div id=\"tables\"></div>\n";
  page += guarded("Thesis Table 3.2", [&] { return table_3_2_section(report); });
  page += guarded("Thesis Table 4.1", [&] { return table_4_1_section(report); });
  page += guarded("On-line image-space culling", [&] { return online_culling_section(report); });
  page += guarded("Radar echo", [&] { return radar_echo_section(report); });
  page += guarded("Polar diagrams", [&] { return polar_diagram_section(report); });
  page += guarded("Slice-wise PVS", [&] { return slice_wise_section(report); });
  page += guarded("Region methods", [&] { return regions_section(report); });
  page += guarded("Region radius sweep", [&] { return region_sweep_section(report); });
  page += guarded("VbAoI", [&] { return vbaoi_table_section(report) + vbaoi_plot_section(report); });
  page += guarded("Scaling", [&] { return scaling_section(report); });
  page += guarded("Speed targets", [&] { return speed_targets_section(report); });
  page += guarded("Fuzzing", [&] { return fuzz_section(report); });
  page += guarded("Map", [&] { return map_section(report, map); });
  page += guarded("Scene", [&] { return scene_section(report); });
  page += "<script>" + std::string(kScript) + "</script>\n</body>\n</html>\n";
  return page;
}

}  // namespace cullcheck::html
