// The report page's plots (page_sections.hpp), built from report.json into svg_plot.hpp's Plots.
#include <map>

#include "reports/html/html_text.hpp"
#include "reports/html/page_sections.hpp"
#include "reports/html/svg_plot.hpp"

namespace cullcheck::html {
namespace {

using nlohmann::json;

std::vector<double> numbers(const json& array) {
  std::vector<double> out;
  if (!array.is_array()) return out;
  for (const json& v : array) out.push_back(v.is_number() ? v.get<double>() : NAN);
  return out;
}

// The series named `name` in `plot`, added at the end when new (series keep first-seen order).
PlotSeries& series(Plot& plot, const std::string& name) {
  for (PlotSeries& s : plot.series)
    if (s.name == name) return s;
  PlotSeries s;
  s.name = name;
  plot.series.push_back(std::move(s));
  return plot.series.back();
}

std::string region_label(const json& r) {
  return text_of(r, "method") + " at radius " + number(value_of(r, "radius")) + " m: " + number(value_of(r, "compute_ms_median")) +
         " ms per PVS, " + percent(value_of(r, "increase_over_point_pvs")) + " over the point PVS";
}

}  // namespace

std::string pareto_section(const json& report) {
  const json& runs = member(report, "runs");
  std::string out = "<section id=\"pareto\"><h2>Speed against accuracy</h2>\n";
  // A method keeps its colour in both plots and in its knob sweeps; each knob has its own dashes.
  std::map<std::string, std::string> colour;
  for (const json& r : runs) colour.emplace(text_of(r, "method"), series_colour(colour.size()));
  const std::map<std::string, std::string> dashes = {{"horizon_bins", "6 3"},  {"quadtree_leaf_size", "2 3"},
                                                     {"delta_radius", "8 3 2 3"}, {"delta_height", "1 2"},
                                                     {"delta_turn", "10 4"}};
  auto method_plot = [&](const std::string& id, const std::string& title, bool zoom) {
    Plot p;
    p.id = id;
    p.title = title;
    p.x_label = "culling time per frame, median (ms)";
    p.y_label = "PVS / witnessed";
    p.log_x = true;
    p.log_y = !zoom;
    for (const json& r : runs) {
      if (zoom && !(value_of(r, "overestimation") <= 2.0)) continue;
      PlotSeries s;
      s.name = text_of(r, "method");
      s.colour = colour[s.name];
      s.joined = false;
      s.points.push_back({value_of(r, "cull_ms_median"), value_of(r, "overestimation"),
                          s.name + ": " + number(value_of(r, "cull_ms_median")) + " ms, PVS " + number(value_of(r, "overestimation")) +
                              "\u00d7 the witnessed set, " + count(value_of(r, "violations")) + " violations"});
      p.series.push_back(std::move(s));
    }
    // Knob sweeps (report.json "knob_sweep"): one dashed series per method and knob, in the method's colour.
    for (const json& k : member(report, "knob_sweep")) {
      if (zoom && !(value_of(k, "overestimation") <= 2.0)) continue;
      const std::string method = text_of(k, "method"), knob = text_of(k, "knob");
      PlotSeries& s = series(p, method + " by " + knob);
      s.dashed = true;
      s.colour = colour.count(method) ? colour[method] : "#555555";
      s.dash = dashes.count(knob) ? dashes.at(knob) : "";
      s.points.push_back({value_of(k, "cull_ms_median"), value_of(k, "overestimation"),
                          method + " with " + knob + " = " + number(value_of(k, "value"), 5) + ": " +
                              number(value_of(k, "cull_ms_median")) + " ms, " + number(value_of(k, "overestimation")) + "\u00d7, " +
                              count(value_of(k, "misses")) + " misses"});
    }
    return p;
  };
  Plot all = method_plot("plot-pareto", "Culling time against over-estimation, every method", false);
  all.note = "Down and to the left is better. 1.0 on the y axis is the oracle's witnessed set: a conservative method cannot "
             "go below it. A point is a method at the knobs it ran with; dashed lines join the values of a swept knob "
             "(--knob-sweep), one dash pattern per knob.";
  out += svg_plot(all);
  Plot zoom = method_plot("plot-pareto-zoom", "The same, near the oracle (PVS at most twice the witnessed set)", true);
  zoom.note = "A linear y axis from the methods within 2x of the witnessed set; methods above it are in the plot before.";
  out += svg_plot(zoom);
  if (const json& sweep = member(report, "knob_sweep"); sweep.is_array() && !sweep.empty()) {
    out += "<table><tr><th class=\"name\">knob</th><th>value</th><th class=\"name\">method</th><th>ms median</th>"
           "<th>PVS</th><th>over-estimation</th><th>misses</th></tr>\n";
    for (const json& k : sweep)
      out += "<tr><td class=\"name\">" + escape(text_of(k, "knob")) + "</td><td>" + number(value_of(k, "value"), 5) +
             (k.value("run_setting", false) ? " (the run's)" : "") + "</td><td class=\"name\">" + escape(text_of(k, "method")) +
             "</td><td>" + number(value_of(k, "cull_ms_median")) + "</td><td>" + number(value_of(k, "pvs_mean_checked_frames"), 4) +
             "</td><td>" + number(value_of(k, "overestimation")) + "</td><td>" +
             (value_of(k, "misses") > 0 ? "<span class=\"bad\">" + count(value_of(k, "misses")) + "</span>" : "0") + "</td></tr>\n";
    out += "</table>\n<p class=\"note\">Misses: objects the main run's oracle saw at its checked frames that the PVS "
           "culled at this setting (the oracle's answers are reused, not cast again; replay with cullcheck verify and "
           "the knob's flag before calling it a violation).</p>\n";
  }

  Plot pixels;
  pixels.id = "plot-pixels";
  pixels.title = "Culling time against misdrawn pixels, per method";
  pixels.x_label = "culling time per frame, median (ms)";
  pixels.y_label = "misdrawn pixels per checked frame, mean";
  pixels.log_x = true;
  pixels.y_from_zero = true;
  pixels.note = "The pixel oracle's id buffer of the whole scene against the PVS's, at every checked frame: what an approximate "
                "method trades for its speed. A conservative method sits on zero.";
  for (const json& r : runs) {
    const json& p = member(r, "pixels");
    if (!p.is_object()) continue;
    PlotSeries& s = series(pixels, text_of(r, "method"));
    s.joined = false;
    s.points.push_back({value_of(r, "cull_ms_median"), value_of(p, "misdrawn_pixels_mean")});
  }
  if (!pixels.series.empty()) out += svg_plot(pixels);

  // Region methods: the cost of a PVS against its size, every radius of the sweep joined.
  Plot regions;
  regions.id = "plot-region-pareto";
  regions.title = "From-region PVS: time per PVS against its size";
  regions.x_label = "time per region PVS, median (ms)";
  regions.y_label = "PVS over the point PVS";
  regions.log_x = true;
  regions.note = "Each point is one method at one region radius (the path's and, joined, the radius sweep's); larger regions "
                 "serve more frames per PVS and keep more objects.";
  for (const json& r : member(report, "region_sweep")) {
    PlotSeries& s = series(regions, text_of(r, "method"));
    s.points.push_back({value_of(r, "compute_ms_median"), value_of(r, "increase_over_point_pvs"), region_label(r)});
  }
  for (const json& r : member(report, "regions")) {
    PlotSeries& s = series(regions, text_of(r, "method") + " (path radius)");
    s.joined = false;
    s.points.push_back({value_of(r, "compute_ms_median"), value_of(r, "increase_over_point_pvs"), region_label(r)});
  }
  if (!regions.series.empty()) out += svg_plot(regions);
  return out + "</section>\n";
}

std::string per_frame_section(const json& report) {
  const json& runs = member(report, "runs");
  bool any = false;
  for (const json& r : runs) any = any || member(r, "per_frame").is_object();
  if (!any) return "";
  Plot time, pvs;
  time.id = "plot-frame-time";
  time.title = "Culling time along the path";
  time.x_label = "frame";
  time.y_label = "culling time (ms)";
  time.log_y = true;
  time.note = "Every frame, every method. Spikes of incremental methods are their re-anchoring frames.";
  pvs.id = "plot-frame-pvs";
  pvs.title = "PVS and witnessed set along the path";
  pvs.x_label = "frame";
  pvs.y_label = "objects";
  pvs.log_y = true;
  pvs.note = "PVS size at every frame; the oracle's witnessed set (dashed) at the frames it checked.";
  const json* witnessed_run = nullptr;
  for (const json& r : runs) {
    const json& f = member(r, "per_frame");
    if (!f.is_object()) continue;
    const std::vector<double> ms = numbers(member(f, "cull_ms")), size = numbers(member(f, "pvs")), frames = numbers(member(f, "frames"));
    PlotSeries& t = series(time, text_of(r, "method"));
    PlotSeries& p = series(pvs, text_of(r, "method"));
    t.markers = p.markers = false;
    for (std::size_t k = 0; k < ms.size() && k < frames.size(); ++k) t.points.push_back({frames[k], ms[k]});
    for (std::size_t k = 0; k < size.size() && k < frames.size(); ++k) p.points.push_back({frames[k], size[k]});
    if (!witnessed_run && member(f, "checked_frames").is_array()) witnessed_run = &f;
  }
  if (witnessed_run) {
    const std::vector<double> frames = numbers(member(*witnessed_run, "checked_frames")),
                              seen = numbers(member(*witnessed_run, "witnessed"));
    PlotSeries& w = series(pvs, "witnessed (oracle)");
    w.dashed = true;
    for (std::size_t k = 0; k < frames.size() && k < seen.size(); ++k) w.points.push_back({frames[k], seen[k]});
  }
  return "<section id=\"per-frame\"><h2>Along the path</h2>\n" + svg_plot(time) + svg_plot(pvs) + "</section>\n";
}

std::string region_sweep_section(const json& report) {
  const json& sweep = member(report, "region_sweep");
  if (!sweep.is_array() || sweep.empty()) return "";
  Plot size;
  size.id = "plot-region-sweep";
  size.title = "Region radius sweep: PVS over the point PVS";
  size.x_label = "region radius (m)";
  size.y_label = "PVS over the point PVS";
  size.y_from_zero = true;
  for (const json& r : sweep) series(size, text_of(r, "method")).points.push_back({value_of(r, "radius"), value_of(r, "increase_over_point_pvs"), region_label(r)});
  Plot serve;
  serve.id = "plot-region-frames";
  serve.title = "Region radius sweep: frames each PVS serves";
  serve.x_label = "region radius (m)";
  serve.y_label = "frames per PVS";
  serve.y_from_zero = true;
  for (const json& r : sweep) series(serve, text_of(r, "method")).points.push_back({value_of(r, "radius"), value_of(r, "frames_per_pvs")});
  return "<section id=\"region-sweep\"><h2>Region radius sweep</h2>\n" + svg_plot(size) + svg_plot(serve) + "</section>\n";
}

std::string vbaoi_plot_section(const json& report) {
  const json& v = member(report, "vbaoi");
  if (!v.is_object()) return "";
  Plot messages, bytes;
  messages.id = "plot-vbaoi-messages";
  messages.title = "VbAoI: messages against clients";
  messages.x_label = "clients";
  messages.y_label = "messages in the simulation";
  messages.log_x = messages.log_y = true;
  messages.note = "Every client publishes the same updates; fewer messages is better where a policy misses none (see the "
                  "table). Broadcast grows with the square of the clients; VbAoI filtered drops what the server proves unseen.";
  bytes = messages;
  bytes.id = "plot-vbaoi-bytes";
  bytes.title = "VbAoI: bytes against clients";
  bytes.y_label = "bytes in the simulation";
  bytes.note = "";
  for (const json& run : member(v, "runs"))
    for (const json& p : member(run, "policies")) {
      std::string name = text_of(p, "policy");
      if (value_of(p, "radius") > 0) name += " " + number(value_of(p, "radius")) + " m";
      series(messages, name).points.push_back({value_of(run, "clients"), value_of(p, "messages")});
      series(bytes, name).points.push_back({value_of(run, "clients"), value_of(p, "bytes")});
    }
  return svg_plot(messages) + svg_plot(bytes);
}

std::string scaling_section(const json& report) {
  const json& rows = member(report, "scaling");
  if (!rows.is_array() || rows.empty()) return "";
  Plot time;
  time.id = "plot-scaling";
  time.title = "Culling time against city size";
  time.x_label = "buildings";
  time.y_label = "culling time per frame, median (ms)";
  time.log_x = time.log_y = true;
  for (const json& row : rows)
    for (const json& m : member(row, "methods"))
      series(time, text_of(m, "method")).points.push_back({value_of(row, "buildings"), value_of(m, "cull_ms_median")});
  return "<section id=\"scaling\"><h2>Scaling</h2>\n" + svg_plot(time) + "</section>\n";
}

}  // namespace cullcheck::html
