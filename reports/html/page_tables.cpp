// The report page's tables and text sections (page_sections.hpp).
#include <algorithm>
#include <cmath>

#include "reports/html/html_text.hpp"
#include "reports/html/page_sections.hpp"
#include "reports/pictures.hpp"

namespace cullcheck::html {
namespace {

using nlohmann::json;

std::string cell(const std::string& text, const char* cls = nullptr) {
  return cls ? "<td class=\"" + std::string(cls) + "\">" + text + "</td>" : "<td>" + text + "</td>";
}
// A header row; a name starting with '<' heads a text column (left-aligned like its cells).
std::string header(std::initializer_list<const char*> names) {
  std::string out = "<tr>";
  for (const char* n : names) {
    const bool text = n[0] == '<';
    out += text ? "<th class=\"name\">" : "<th>";
    out += escape(text ? n + 1 : n);
    out += "</th>";
  }
  return out + "</tr>\n";
}
std::string yes_no(const json& v) { return v.is_boolean() ? (v.get<bool>() ? "yes" : "no") : "\u2013"; }
std::string colour_hex(Rgb c) {
  char buffer[8];
  std::snprintf(buffer, sizeof buffer, "#%02x%02x%02x", c.r, c.g, c.b);
  return buffer;
}
std::string violations_cell(double v) { return v > 0 ? cell("<span class=\"bad\">" + count(v) + "</span>") : cell(count(v)); }

}  // namespace

std::string gate_section(const json& report) {
  const json& gate = member(report, "gate");
  if (!gate.is_object()) return "";
  const bool passed = gate.value("passed", false);
  std::string out = "<section id=\"gate\"><h2>Gate</h2>\n<div class=\"verdict " + std::string(passed ? "passed" : "failed") +
                    "\" id=\"gate-verdict\"><b>" + (passed ? "PASSED" : "FAILED") + "</b> (exit code " +
                    count(value_of(gate, "exit_code")) + "): " + count(value_of(gate, "conservative_violations")) +
                    " objects seen but culled by methods that claim to be conservative, " +
                    count(value_of(gate, "conservative_misdrawn_pixels")) + " misdrawn pixels of theirs, " +
                    count(value_of(gate, "frames_over_pixel_budget")) + " frames over an approximate method's pixel budget, " +
                    count(value_of(gate, "section_violations")) + " violations in the report's other sections" +
                    (gate.value("subject_failed", false) ? "; an outside subject failed (crashed, hung or broke the protocol)" : "") +
                    (gate.value("nothing_witnessed", false) ? "; the oracle saw nothing on the path, which proves nothing" : "") +
                    ".</div>\n";
  const json& checks = member(gate, "checks");
  if (checks.is_array() && !checks.empty()) {
    out += "<table>" + header({"<method", "<check", "<outcome", "<detail"});
    for (const json& c : checks) {
      const std::string outcome = text_of(c, "outcome");
      out += "<tr>" + cell(escape(text_of(c, "method")), "name") + cell(escape(text_of(c, "check")), "name") +
             cell(outcome == "passed" ? escape(outcome) : "<span class=\"bad\">" + escape(outcome) + "</span>", "name") +
             cell(escape(text_of(c, "detail", text_of(c, "message"))), "name") + "</tr>\n";
    }
    out += "</table>\n";
  }
  if (const json& aborted = member(report, "aborted"); aborted.is_object())
    out += "<p class=\"problem\">The run stopped early: " + escape(text_of(aborted, "method")) + " (" + escape(text_of(aborted, "kind")) +
           "): " + escape(text_of(aborted, "message")) + "</p>\n";
  return out + "</section>\n";
}

std::string summary_section(const json& report) {
  const json& runs = member(report, "runs");
  if (!runs.is_array()) return "";
  const bool pixels = member(member(report, "pixel_oracle"), "enabled").is_boolean() && report["pixel_oracle"]["enabled"].get<bool>();
  std::string out = "<section id=\"summary\"><h2>Methods along the path</h2>\n<p class=\"note\">Culling time per frame (median and "
                    "95th percentile over every frame); PVS and witnessed sizes averaged over the frames the oracle checked; "
                    "over-estimation = PVS / witnessed. A violation is an object the oracle saw that the method culled.</p>\n<table>";
  out += pixels ? header({"<method", "frames", "ms median", "ms p95", "PVS", "witnessed", "over-estimation", "violations",
                          "frames with violations", "misdrawn px / frame", "error frames", "claims conservative"})
                : header({"<method", "frames", "ms median", "ms p95", "PVS", "witnessed", "over-estimation", "violations",
                          "frames with violations", "claims conservative"});
  for (const json& r : runs) {
    std::string name = escape(text_of(r, "method"));
    if (r.value("outside", false)) name += " <small>(outside subject)</small>";
    out += "<tr>" + cell(name, "name") + cell(count(value_of(r, "frames"))) + cell(number(value_of(r, "cull_ms_median"))) +
           cell(number(value_of(r, "cull_ms_p95"))) + cell(number(value_of(r, "pvs_mean_checked_frames"), 4)) +
           cell(number(value_of(r, "witnessed_mean"), 4)) + cell(number(value_of(r, "overestimation"))) +
           violations_cell(value_of(r, "violations")) + cell(count(value_of(r, "frames_with_violations")));
    if (pixels) {
      const json& p = member(r, "pixels");
      out += cell(number(value_of(p, "misdrawn_pixels_mean"))) + cell(count(value_of(p, "error_frames")));
    }
    out += cell(yes_no(member(r, "claims_conservative"))) + "</tr>\n";
  }
  out += "</table>\n";
  for (const json& r : runs) {
    const json& replays = member(r, "violation_replays");
    if (!replays.is_array() || replays.empty()) continue;
    out += "<h3>" + escape(text_of(r, "method")) + ": violations (the first " + std::to_string(replays.size()) + " of " +
           count(value_of(r, "violations")) + ")</h3>\n";
    for (const json& x : replays)
      out += "<p class=\"note\">frame " + count(value_of(x, "frame")) + ", object " + count(value_of(x, "building")) + " seen by " +
             escape(text_of(x, "model")) + ": " + escape(text_of(x, "witness")) + "</p>\n" + replay_block(text_of(x, "replay"));
  }
  if (const json& skipped = member(report, "skipped_methods"); skipped.is_array() && !skipped.empty()) {
    out += "<p class=\"note\">Not run on this scene:";
    for (const json& s : skipped) out += " " + escape(text_of(s, "method")) + " (" + escape(text_of(s, "reason")) + ");";
    out += "</p>\n";
  }
  return out + "</section>\n";
}

std::string claims_section(const json& report) {
  const json& claims = member(report, "claims");
  if (!claims.is_array()) return "";
  std::size_t refuted = 0;
  for (const json& c : claims) refuted += c.value("holds", true) ? 0 : 1;
  std::string out = "<section id=\"claims\"><h2>Claims ledger</h2>\n<p class=\"note\">" + std::to_string(claims.size()) +
                    " claims checked, " + std::to_string(refuted) +
                    " refuted. A refuted claim carries the one command that replays its counterexample.</p>\n<table>" +
                    header({"<claim", "<source", "<statement", "<verdict", "frames checked", "violations"});
  for (const json& c : claims) {
    const bool holds = c.value("holds", true);
    out += "<tr id=\"claim-" + escape(text_of(c, "id")) + "\">" + cell("<b>" + escape(text_of(c, "id")) + "</b>", "name") +
           cell(escape(text_of(c, "source")), "name") + cell(escape(text_of(c, "statement")), "name") +
           cell(holds ? "<span class=\"holds\">holds</span>" : "<span class=\"refuted\">REFUTED</span>", "name") +
           cell(count(value_of(c, "frames_checked"))) + cell(count(value_of(c, "violations"))) + "</tr>\n";
    const json& counterexample = member(c, "counterexample");
    if (!holds && counterexample.is_object())
      out += "<tr><td colspan=\"6\" class=\"name\">" + escape(text_of(counterexample, "detail")) +
             replay_block(text_of(counterexample, "replay")) + "</td></tr>\n";
  }
  return out + "</table>\n</section>\n";
}

std::string table_3_2_section(const json& report) {
  const json& speedups = member(report, "speedups");
  if (!speedups.is_array() || speedups.empty()) return "";
  std::string out = "<section id=\"table-3-2\"><h2>Thesis Table 3.2: culling-time speed-ups</h2>\n<p class=\"note\">Measured in "
                    "this run on this machine as ratios of per-frame culling time (the slower method's over the faster's); "
                    "the thesis's figures are from its Pentium IV. Ratios, not seconds, are what carries over between "
                    "machines.</p>\n<table>" +
                    header({"<faster", "<than", "median ratio", "p95 ratio", "mean ratio", "cells tested ratio", "thesis"});
  for (const json& s : speedups)
    out += "<tr>" + cell(escape(text_of(s, "faster")), "name") + cell(escape(text_of(s, "than")), "name") +
           cell(number(value_of(s, "cull_ms_median_ratio")) + "\u00d7") + cell(number(value_of(s, "cull_ms_p95_ratio")) + "\u00d7") +
           cell(number(value_of(s, "cull_ms_mean_ratio")) + "\u00d7") + cell(number(value_of(s, "cells_tested_ratio"))) +
           cell(std::isfinite(value_of(s, "thesis_table_3_2_culling_time"))
                    ? number(value_of(s, "thesis_table_3_2_culling_time")) + "\u00d7"
                    : "\u2013") +
           "</tr>\n";
  return out + "</table>\n</section>\n";
}

std::string table_4_1_section(const json& report) {
  const json& t = member(report, "table_4_1");
  if (!t.is_object()) return "";
  const json& path = member(t, "path");
  std::string out = "<section id=\"table-4-1\"><h2>Thesis Table 4.1: from-region PVS on the plaza walk</h2>\n<p class=\"note\">" +
                    escape(text_of(path, "kind")) + " of " + count(value_of(path, "frames")) + " frames, region radius " +
                    number(value_of(t, "radius")) + " m, " + count(value_of(t, "oracle_frames")) +
                    " frames checked by the oracle. Increase = PVS over Method 1's at 60 degrees, beside the thesis's.</p>\n<table>" +
                    header({"<method", "<thesis's method", "angle", "PVS", "increase", "thesis", "violations", "ms / PVS", "frames / PVS"});
  for (const json& r : member(t, "rows")) {
    const bool claimed = r.value("claims_conservative", true);
    out += "<tr>" + cell(escape(text_of(r, "method")) + (claimed ? "" : " <small>(not claimed conservative)</small>"), "name") +
           cell(escape(text_of(r, "thesis_method")), "name") + cell(number(value_of(r, "viewing_angle")) + "\u00b0") +
           cell(number(value_of(r, "pvs_mean"), 4)) + cell(percent(value_of(r, "increase_over_method_1_at_60"))) +
           cell(percent(value_of(r, "thesis_increase"))) + violations_cell(value_of(r, "violations")) +
           cell(number(value_of(r, "compute_ms_median"))) + cell(number(value_of(r, "frames_per_pvs"))) + "</tr>\n";
  }
  out += "</table>\n";
  for (const json& d : member(t, "disc_witnessed"))
    out += "<p class=\"note\">At " + number(value_of(d, "viewing_angle")) + " degrees the oracle's witnessed union over each disc is " +
           percent(value_of(d, "witnessed_increase")) + " above what its centre sees (" + number(value_of(d, "witnessed_union_mean"), 4) +
           " against " + number(value_of(d, "witnessed_centre_mean"), 4) + " objects): no conservative region method can do "
           "better than that on this walk." +
           (d.contains("oh_os_union_increase")
                ? " OH(OS)'s own point PVS over " + number(value_of(d, "oh_os_union_eyes")) + " eyes of the disc adds up to " +
                      percent(value_of(d, "oh_os_union_increase")) +
                      " over the point PVS: the floor of a region method that keeps OH(OS)'s PVS at every eye."
                : std::string()) +
           "</p>\n";
  return out + "</section>\n";
}

std::string online_culling_section(const json& report) {
  const json& t = member(report, "online_culling");
  if (!t.is_object()) return "";
  std::string out =
      "<section id=\"online-culling\"><h2>On-line image-space culling (Wang et al. 2001): Table 1 in kind</h2>\n<p class=\"note\">"
      "Street walks on generated cities; sent = polygons (frustum culling and OH(OS) send whole buildings); CR_v and CR_o as "
      "Fig. 14 defines them; misdrawn = pixels whose full-scene object the PVS lacks. The paper's frame rates depend on its "
      "graphics hardware: compare the ratios.</p>\n<table>" +
      header({"polygons", "<method", "ms median", "ms p95", "critical frames", "critical ms", "sent", "CR_v", "CR_o", "time / OH(OS)",
              "error frames", "misdrawn"});
  for (const json& city : member(t, "table_1"))
    for (const json& r : member(city, "rows"))
      out += "<tr>" + cell(count(value_of(city, "polygons"))) + cell(escape(text_of(r, "method")), "name") +
             cell(number(value_of(r, "cull_ms_median"))) + cell(number(value_of(r, "cull_ms_p95"))) +
             cell(r.contains("critical_frames") ? count(value_of(r, "critical_frames")) : "\u2013") +
             cell(r.contains("critical_ms_median") ? number(value_of(r, "critical_ms_median")) : "\u2013") +
             cell(number(value_of(r, "polygons_sent_mean"), 5)) + cell(number(value_of(r, "cr_v_mean"))) +
             cell(number(value_of(r, "cr_o_mean"))) +
             cell(r.contains("time_median_over_oh_os") ? number(value_of(r, "time_median_over_oh_os")) + "\u00d7" : "1\u00d7") +
             cell(count(value_of(r, "error_frames"))) + cell(count(value_of(r, "misdrawn_pixels"))) + "</tr>\n";
  out += "</table>\n";
  if (t.contains("delta_sweep")) {
    out += "<h3>The \u0394 \u00d7 s sweep (Fig. 11, 12) and the trade</h3>\n<table>" +
           header({"<method", "\u0394", "s", "ms median", "ms p95", "sent", "critical frames", "error frames", "misdrawn / frame"});
    for (const json& r : member(member(t, "delta_sweep"), "rows")) {
      const json& p = member(r, "parameters");
      out += "<tr>" + cell(escape(text_of(r, "method")), "name") +
             cell(p.contains("shrink_pixels") ? count(value_of(p, "shrink_pixels")) : "\u2013") +
             cell(p.contains("mask_size") ? count(value_of(p, "mask_size")) : "\u2013") + cell(number(value_of(r, "cull_ms_median"))) +
             cell(number(value_of(r, "cull_ms_p95"))) + cell(number(value_of(r, "polygons_sent_mean"), 5)) +
             cell(r.contains("critical_frames") ? count(value_of(r, "critical_frames")) : "\u2013") +
             cell(count(value_of(r, "error_frames"))) + cell(number(value_of(r, "misdrawn_pixels_mean"))) + "</tr>\n";
    }
    out += "</table>\n";
  }
  if (t.contains("long_walk"))
    for (const json& r : member(member(t, "long_walk"), "rows"))
      out += "<p class=\"note\">Long walk, " + escape(text_of(r, "method")) + ": misdrawn pixels in " + count(value_of(r, "error_frames")) +
             " of " + count(value_of(member(t, "long_walk"), "frames")) + " frames (the paper: 158 of 11,558 at \u0394 = 6), at most " +
             count(value_of(r, "most_misdrawn_in_a_frame")) + " in one.</p>\n";
  return out + "</section>\n";
}

std::string radar_echo_section(const json& report) {
  const json& t = member(report, "radar_echo");
  if (!t.is_object()) return "";
  std::string out =
      "<section id=\"radar-echo\"><h2>Radar echo over terrain (thesis ch. 3.3): Table 3.3 in kind</h2>\n<p class=\"note\">"
      "The transmitter " + number(value_of(t, "height_m")) + " m above the ground at each terrain's centre; 60 degrees centred "
      "north, and the full circle. Missed = triangles the oracle's rays hit first that the PVS lacks; both rules claim none. The "
      "thesis's times (60 degrees) are from a Pentium IV and a GeForce4 MX: compare how they grow, not their size.</p>\n";
  for (const json& terrain : member(t, "terrains")) {
    out += "<h3>" + escape(text_of(terrain, "summary")) + "</h3>\n<p class=\"note\">" + count(value_of(terrain, "triangles")) +
           " triangles; the oracle witnessed " + count(value_of(member(terrain, "oracle")[0], "witnessed")) + " (60 degrees) and " +
           count(value_of(member(terrain, "oracle")[1], "witnessed")) + " (360 degrees).</p>\n<table>" +
           header({"grid", "degrees", "<rule", "ms median", "ms p95", "visible", "tested", "missed", "PVS / witnessed", "thesis ms"});
    for (const json& row : member(terrain, "rows"))
      for (const json& r : member(row, "rules")) {
        const std::string g = count(value_of(row, "grid"));
        const bool thesis = text_of(terrain, "name") == "generated" && value_of(row, "sector_deg") == 60 && text_of(r, "rule") == "thesis" &&
                            member(t, "thesis_ms_60deg").contains(g);
        out += "<tr>" + cell(g + "\u00d7" + g) + cell(count(value_of(row, "sector_deg"))) + cell(escape(text_of(r, "rule")), "name") +
               cell(number(value_of(r, "ms_median"))) + cell(number(value_of(r, "ms_p95"))) + cell(count(value_of(r, "visible"))) +
               cell(count(value_of(r, "triangles_tested"))) + violations_cell(value_of(r, "missed")) +
               cell(number(value_of(r, "pvs_over_witnessed"))) + cell(thesis ? count(value_of(member(t, "thesis_ms_60deg"), g.c_str())) : "") + "</tr>\n";
      }
    out += "</table>\n";
    for (const json& file : member(terrain, "echo_files")) {
      const std::string path = file.is_string() ? file.get<std::string>() : "";
      const std::string name = path.substr(path.find_last_of('/') == std::string::npos ? 0 : path.find_last_of('/') + 1);
      out += "<figure class=\"echo\"><img src=\"" + escape(name) + "\" alt=\"" + escape(name) + "\" width=\"256\"><figcaption>" +
             escape(name) + "</figcaption></figure>\n";
    }
  }
  if (t.contains("moving_platform")) {
    const json& m = member(t, "moving_platform");
    out += "<p class=\"note\">Moving platform: " + count(value_of(m, "positions")) + " rotations " + number(value_of(m, "step_m")) +
           " m apart, each from scratch in " + number(value_of(m, "ms_median")) + " ms (median; p95 " + number(value_of(m, "ms_p95")) +
           "); the previous rotation's PVS held " + number(100.0 * value_of(m, "previous_pvs_share_median")) + "%" +
           " of each. A region echo reused while the platform stays within its radius:</p>\n<table>" +
           header({"radius (m)", "region echoes", "rotations / echo", "ms / echo median", "speedup", "PVS / rotation's", "missed"});
    for (const json& r : member(m, "regions"))
      out += "<tr>" + cell(number(value_of(r, "radius_m"))) + cell(count(value_of(r, "regions"))) +
             cell(number(value_of(r, "rotations_per_region"))) + cell(count(value_of(r, "region_ms_median"))) +
             cell(number(value_of(r, "speedup"))) + cell(number(value_of(r, "pvs_over_point_median"))) +
             violations_cell(value_of(r, "missed")) + "</tr>\n";
    out += "</table>\n";
  }
  return out + "</section>\n";
}

std::string polar_diagram_section(const json& report) {
  const json& t = member(report, "polar_diagram");
  if (!t.is_object()) return "";
  std::string out =
      "<section id=\"polar-diagram\"><h2>Polar diagrams (Ortega et al.) against CGAL's visibility polygon</h2>\n<p class=\"note\">"
      "Plan view, level walks. Both sides exact: any frame where the visible sets differ is counted as a mismatch and fails the "
      "gate. The paper builds each diagram in 100 ms (600 buildings, 45,000 vertices, Pentium IV 2.4 GHz) and throws O(2k) rays "
      "for k visible buildings.</p>\n<table>" +
      header({"<city", "buildings", "vertices", "four diagrams ms", "one diagram ms", "fan grids ms", "CGAL build ms"});
  for (const json& c : member(t, "cities"))
    out += "<tr>" + cell(escape(text_of(c, "scene")), "name") + cell(count(value_of(c, "buildings"))) + cell(count(value_of(c, "vertices"))) +
           cell(number(value_of(c, "diagrams_ms"))) + cell(number(value_of(c, "one_diagram_ms"))) + cell(number(value_of(c, "fan_build_ms"))) +
           cell(number(value_of(c, "cgal_build_ms"))) + "</tr>\n";
  out += "</table>\n<table>" + header({"<city", "view", "frames", "fan ms median", "fan ms p95", "CGAL ms median", "CGAL / fan", "k",
                                        "visible edges", "rays", "rays / 2k", "mismatches"});
  for (const json& c : member(t, "cities"))
    for (const json& w : member(c, "walks"))
      out += "<tr>" + cell(escape(text_of(c, "scene")), "name") + cell(count(value_of(w, "hfov_deg"))) + cell(count(value_of(w, "frames_compared"))) +
             cell(number(value_of(w, "fan_ms_median"))) + cell(number(value_of(w, "fan_ms_p95"))) + cell(number(value_of(w, "cgal_ms_median"))) +
             cell(number(value_of(w, "cgal_over_fan_median"))) + cell(number(value_of(w, "visible_mean"))) +
             cell(number(value_of(w, "visible_edges_mean"))) + cell(number(value_of(w, "rays_mean"))) +
             cell(number(value_of(w, "rays_per_2k_median"))) + violations_cell(value_of(w, "mismatches")) + "</tr>\n";
  out += "</table>\n";
  return out + "</section>\n";
}

std::string slice_wise_section(const json& report) {
  const json& t = member(report, "slice_wise");
  if (!t.is_object()) return "";
  std::string out =
      "<section id=\"slice-wise\"><h2>Slice-wise PVS (Yilmaz &amp; Gudukbay): Tables 1-3, Fig. 7</h2>\n<p class=\"note\">"
      "View cells of " + number(value_of(t, "cell_side_m")) + " m along a street walk; occlusion queries exact about coverage "
      "(engine/slice_wise/occlusion_buffer.hpp). The paper renders 49% of the building-level triangles. 'Best form' keeps every "
      "triangle the oracle witnessed from the checked cells with one L/vertical/horizontal form (or, on rows marked 'both "
      "axes', one on each vertical axis at once): what three bytes could do at best. A witnessed triangle outside the kept "
      "slices fails the gate, unless the ray met it at an edge where a kept face turned to the eye draws the same point."
      "</p>\n<table>" +
      header({"<city", "<occluders", "objects", "triangles", "cells", "PVS ms / cell", "PVS objects", "tris / frame slice-wise",
              "building-level", "share", "best form (checked cells)", "witnessed", "violations"});
  for (const json& c : member(t, "cities"))
    for (const json& r : member(c, "runs")) {
      const json &t1 = member(c, "table_1"), &t2 = member(r, "table_2"), &t3 = member(r, "table_3"), &b = member(r, "bound");
      out += "<tr>" + cell(escape(text_of(c, "city")), "name") +
             cell(escape(text_of(r, "shrinking")) + (r.value("self_occlusion", false) ? " + self" : "") +
                      (r.value("both_vertical_axes", false) ? ", both axes" : ""), "name") +
             cell(count(value_of(t1, "objects"))) + cell(count(value_of(t1, "triangles"))) + cell(count(value_of(t2, "cells"))) +
             cell(number(value_of(t2, "pvs_ms_per_cell_median"))) + cell(number(value_of(t2, "pvs_objects_median"))) +
             cell(count(value_of(t3, "slice_wise_triangles_mean"))) + cell(count(value_of(t3, "building_level_triangles_mean"))) +
             cell(number(100 * value_of(t3, "slice_over_building")) + "%") +
             cell(number(100 * value_of(b, "best_form_over_whole")) + "%") + cell(number(100 * value_of(b, "witnessed_over_whole")) + "%") +
             violations_cell(value_of(member(r, "oracle"), "violations")) + "</tr>\n";
    }
  out += "</table>\n";
  return out + replay_block(text_of(t, "replay")) + "</section>\n";
}

std::string regions_section(const json& report) {
  const json& regions = member(report, "regions");
  if (!regions.is_array() || regions.empty()) return "";
  std::string out = "<section id=\"regions\"><h2>Region methods along the path</h2>\n<table>" +
                    header({"<method", "radius (m)", "<placement", "PVS computed", "frames / PVS", "ms / PVS median", "PVS",
                            "over point PVS", "witnessed", "violations"});
  for (const json& r : regions) {
    const bool claimed = r.value("claims_conservative", true);
    out += "<tr>" + cell(escape(text_of(r, "method")) + (claimed ? "" : " <small>(not claimed conservative)</small>"), "name") +
           cell(number(value_of(r, "radius"))) + cell(escape(text_of(r, "placement")), "name") + cell(count(value_of(r, "pvs_computed"))) +
           cell(number(value_of(r, "frames_per_pvs"))) + cell(number(value_of(r, "compute_ms_median"))) +
           cell(number(value_of(r, "pvs_mean"), 4)) + cell(percent(value_of(r, "increase_over_point_pvs"))) +
           cell(number(value_of(r, "witnessed_mean"), 4)) + violations_cell(value_of(r, "violations")) + "</tr>\n";
  }
  out += "</table>\n";
  for (const json& r : regions)
    for (const json& x : member(r, "violation_replays"))
      out += "<p class=\"note\">" + escape(text_of(r, "method")) + ", frame " + count(value_of(x, "frame")) + ", object " +
             count(value_of(x, "building")) + ": " + escape(text_of(x, "witness")) + "</p>\n" + replay_block(text_of(x, "replay"));
  return out + "</section>\n";
}

std::string vbaoi_table_section(const json& report) {
  const json& v = member(report, "vbaoi");
  if (!v.is_object()) return "";
  const json& g = member(v, "graph");
  std::string out = "<section id=\"vbaoi\"><h2>VbAoI: messages against clients</h2>\n<p class=\"note\">The navigable-region graph of " +
                    count(value_of(g, "buildings")) + " buildings: " + count(value_of(g, "nodes")) + " nodes built in " +
                    number(value_of(g, "build_seconds")) + " s with " + escape(text_of(g, "method")) + "; PVSo " +
                    number(value_of(member(g, "pvs_o"), "mean")) + " objects on average (" +
                    percent(value_of(g, "pvs_o_fraction_of_city")).substr(1) + " of the city), " +
                    count(value_of(g, "invariant_violations")) + " invariant violations.</p>\n<table>" +
                    header({"<clients", "<policy", "radius (m)", "messages", "bytes", "messages vs VbAoI", "deliveries vs limit",
                            "missed updates", "lost updates"});
  for (const json& run : member(v, "runs"))
    for (const json& p : member(run, "policies"))
      out += "<tr>" + cell(count(value_of(run, "clients")), "name") + cell(escape(text_of(p, "policy")), "name") +
             cell(value_of(p, "radius") > 0 ? number(value_of(p, "radius")) : "\u2013") + cell(count(value_of(p, "messages"))) +
             cell(count(value_of(p, "bytes"))) + cell(number(value_of(p, "messages_vs_vbaoi")) + "\u00d7") +
             cell(p.contains("deliveries_vs_limit") ? number(value_of(p, "deliveries_vs_limit")) + "\u00d7" : "\u2013") +
             violations_cell(value_of(p, "missed_updates")) + cell(count(value_of(p, "lost_updates"))) + "</tr>\n";
  out += "</table>\n";
  for (const json& run : member(v, "runs"))
    if (!text_of(run, "replay").empty()) {
      out += "<p class=\"note\">Replay the " + count(value_of(run, "clients")) + "-client simulation:</p>" + replay_block(text_of(run, "replay"));
      break;
    }
  return out + "</section>\n";
}

std::string speed_targets_section(const json& report) {
  const json& rows = member(member(report, "speed_targets"), "rows");
  if (!rows.is_array() || rows.empty()) return "";
  const bool before = std::any_of(rows.begin(), rows.end(), [](const json& r) { return r.contains("before"); });
  std::string out =
      "<section id=\"speed-targets\"><h2>Speed targets</h2>\n<p class=\"note\">Issue 17's targets, each figure derived from "
      "this report's own fields (the column on the right says which)" +
      std::string(before ? "; before: the baseline report given to <code>report --baseline</code>" : "") + ".</p>\n<table>" +
      (before ? header({"<target", "<goal", "before", "figure", "<met", "<from"}) : header({"<target", "<goal", "figure", "<met", "<from"}));
  for (const json& r : rows) {
    auto figure = [&](const char* key) {
      if (!r.contains(key)) return cell("\u2013");
      return r[key].is_null() ? cell("<span class=\"bad\">violations</span>") : cell(number(r[key].get<double>()));
    };
    const bool met = r.value("met", false);
    out += "<tr>" + cell(escape(text_of(r, "id")), "name") + cell(escape(text_of(r, "goal")), "name") + (before ? figure("before") : "") +
           figure("figure") + cell(met ? "yes" : "<span class=\"bad\">no</span>", "name") + cell(escape(text_of(r, "from")), "name") +
           "</tr>\n";
  }
  return out + "</table>\n</section>\n";
}

std::string fuzz_section(const json& report) {
  std::string out;
  for (const char* key : {"fuzz", "soak"}) {
    const json& f = member(report, key);
    if (!f.is_object()) continue;
    out += "<h3>" + std::string(key == std::string("fuzz") ? "Fuzzed subject" : "Soak of the built-in conservative methods") +
           ": " + escape(text_of(f, "subject")) + "</h3>\n<p class=\"note\">" + count(value_of(f, "cases")) + " cases in " +
           number(value_of(f, "seconds_total")) + " s" +
           (member(f, "failure").is_object() || !text_of(f, "counterexample").empty()
                ? ": <span class=\"bad\">a counterexample was found</span>, shrunk to " + escape(text_of(f, "counterexample"))
                : ": no counterexample") +
           ".</p>\n";
  }
  return out.empty() ? "" : "<section id=\"fuzzing\"><h2>Fuzzing</h2>\n" + out + "</section>\n";
}

std::string scene_section(const json& report) {
  const json& s = member(report, "scene");
  std::string out = "<section id=\"scene\"><h2>Scene, oracle and machine</h2>\n<table>" + header({"<", "<"});
  auto row = [&](const std::string& k, const std::string& v) { out += "<tr>" + cell(escape(k), "name") + cell(v, "name") + "</tr>\n"; };
  row("scene", "<code>" + escape(text_of(s, "replay_flags")) + "</code>");
  row("model", escape(text_of(s, "model")));
  row("buildings / meshes / triangles", count(value_of(s, "building_count")) + " / " + count(value_of(s, "mesh_count")) + " / " +
                                            count(value_of(s, "triangle_count")));
  if (const json& i = member(s, "import"); i.is_object())
    row("imported", count(value_of(i, "features")) + " features: " + count(value_of(i, "buildings")) + " buildings, " +
                        count(value_of(i, "heights_defaulted")) + " heights defaulted, " + count(value_of(i, "rings_repaired")) +
                        " rings repaired, " + count(value_of(i, "holes_filled")) + " holes filled, " +
                        count(value_of(i, "skipped_invalid")) + " invalid polygons skipped, CRS " + escape(text_of(i, "crs")));
  const json& o = member(report, "oracle");
  row("oracle", count(value_of(o, "frames_checked")) + " frames checked (every " + count(value_of(o, "oracle_stride")) + "th), " +
                    count(value_of(o, "rays_cast")) + " rays (" + count(value_of(o, "rays_skipped")) +
                    " skipped: their object already witnessed), " + number(value_of(o, "rays_per_second")) + " rays/s (bare Embree " +
                    number(value_of(o, "bare_embree_rays_per_second")) + " one by one, " +
                    number(value_of(o, "bare_embree_packet_rays_per_second")) + " in packets)");
  const json& m = member(report, "machine");
  row("machine", escape(text_of(m, "system")) + ", " + count(value_of(m, "hardware_threads")) + " threads, " +
                     escape(text_of(m, "compiler")) + ", " + escape(text_of(m, "build_type")));
  return out + "</table>\n</section>\n";
}

std::string map_section(const json& report, const PageMap& map) {
  const json& m = member(report, "map");
  std::string out = "<section id=\"map\" class=\"map\"><h2>Top-down map</h2>\n";
  if (!m.is_object())
    return out + "<p class=\"problem\">This report has no map frame: " +
           escape(text_of(report, "map_problem", "no frame was checked by the oracle")) + ".</p></section>\n";
  const std::size_t missed = member(m, "missed").is_array() ? m["missed"].size() : 0;
  out += "<p class=\"note\">" + escape(text_of(m, "method")) + " at frame " + count(value_of(m, "frame")) + " (" +
         escape(text_of(m, "chosen_by")) + "): PVS " + std::to_string(member(m, "pvs").size()) + " objects, the oracle saw " +
         std::to_string(member(m, "seen").size()) + ", " + count(value_of(m, "overestimate")) + " over-estimated, " +
         (missed > 0 ? "<span class=\"bad\">" + std::to_string(missed) + " missed</span>" : std::string("none missed")) +
         ". North is up.</p>\n<p class=\"note\">";
  const std::pair<const char*, Rgb> legend[] = {{"view volume", map_colours::kViewVolume},  {"visible (in the PVS, seen)", map_colours::kVisible},
                                                {"over-estimate (in the PVS, not seen)", map_colours::kOverEstimate},
                                                {"culled", map_colours::kCulled}, {"missed (seen, culled)", map_colours::kMissed},
                                                {"witness ray", map_colours::kWitnessRay}, {"eye", map_colours::kEye}};
  for (const auto& [name, colour] : legend) out += "<span class=\"swatch\" style=\"background:" + colour_hex(colour) + "\"></span>" + escape(name);
  out += "</p>\n";
  if (map.png.empty()) return out + "<p class=\"problem\">No map drawn: " + escape(map.problem) + "</p></section>\n";
  return out + "<img id=\"map-image\" alt=\"top-down map of frame " + count(value_of(m, "frame")) +
         "\" src=\"data:image/png;base64," + base64(map.png) + "\">\n</section>\n";
}

}  // namespace cullcheck::html
