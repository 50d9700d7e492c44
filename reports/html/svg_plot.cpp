#include "reports/html/svg_plot.hpp"

#include <algorithm>
#include <cmath>

#include "reports/html/html_text.hpp"

namespace cullcheck::html {
namespace {

// The largest of 1, 2, 5 x 10^k not above `raw`... rounded up: the step of about `target` ticks.
double nice_step(double span, int target) {
  const double raw = span / std::max(1, target);
  const double power = std::pow(10.0, std::floor(std::log10(raw)));
  for (double m : {1.0, 2.0, 5.0, 10.0})
    if (m * power >= raw) return m * power;
  return 10.0 * power;
}

}  // namespace

Axis::Axis(const std::vector<double>& values, bool logarithmic, bool include_zero) : log_(logarithmic) {
  double lo = INFINITY, hi = -INFINITY;
  for (double v : values)
    if (drawable(v)) lo = std::min(lo, v), hi = std::max(hi, v);
  if (log_) {
    if (!(lo <= hi)) lo = 1.0, hi = 10.0;
    lo_ = std::pow(10.0, std::floor(std::log10(lo)));
    hi_ = std::pow(10.0, std::ceil(std::log10(hi)));
    if (hi_ <= lo_) hi_ = lo_ * 10.0;
    // Every decade when there are few, else every second or third one.
    const int decades = int(std::lround(std::log10(hi_ / lo_)));
    const int every = decades <= 6 ? 1 : (decades + 5) / 6;
    for (int k = 0; k <= decades; k += every) ticks_.push_back(lo_ * std::pow(10.0, k));
    return;
  }
  if (!(lo <= hi)) lo = 0.0, hi = 1.0;
  if (include_zero) lo = std::min(lo, 0.0), hi = std::max(hi, 0.0);
  if (hi == lo) {  // one value: a unit-wide range around it
    const double pad = lo == 0.0 ? 1.0 : std::fabs(lo) * 0.5;
    lo -= pad, hi += pad;
  }
  const double step = step_ = nice_step(hi - lo, 5);
  lo_ = std::floor(lo / step) * step;
  hi_ = std::ceil(hi / step) * step;
  for (int k = 0;; ++k) {
    const double t = lo_ + k * step;
    if (t > hi_ + step * 1e-9) break;
    ticks_.push_back(std::fabs(t) < step * 1e-9 ? 0.0 : t);
  }
}

std::string Axis::tick_label(double tick) const {
  char buffer[32];
  if (log_) {
    const int power = int(std::lround(std::log10(tick)));
    if (power >= 4 || power < -3) std::snprintf(buffer, sizeof buffer, "1e%d", power);
    else std::snprintf(buffer, sizeof buffer, "%.*f", std::max(0, -power), tick);
    return buffer;
  }
  // The step is 1, 2 or 5 x 10^k: -k decimals show every tick exactly (2.5 steps do not occur).
  const int decimals = std::max(0, -int(std::floor(std::log10(step_) + 1e-9)));
  std::snprintf(buffer, sizeof buffer, "%.*f", decimals, tick);
  return std::string(buffer) == "-0" ? "0" : buffer;
}

bool Axis::drawable(double v) const { return std::isfinite(v) && (!log_ || v > 0.0); }

double Axis::pixel(double v, double from, double to) const {
  const double t = log_ ? std::log10(v / lo_) / std::log10(hi_ / lo_) : (v - lo_) / (hi_ - lo_);
  return from + t * (to - from);
}

std::string series_colour(std::size_t n) {
  // Okabe and Ito's palette, then Tableau's, for more series than eight.
  static const char* kPalette[] = {"#0072b2", "#d55e00", "#009e73", "#cc79a7", "#e69f00", "#56b4e9", "#000000", "#f0e442",
                                   "#8c564b", "#7f7f7f", "#bcbd22", "#17becf", "#9467bd", "#1f77b4", "#ff7f0e", "#2ca02c"};
  return kPalette[n % (sizeof kPalette / sizeof kPalette[0])];
}

std::string svg_plot(const Plot& plot) {
  std::vector<double> xs, ys;
  for (const PlotSeries& s : plot.series)
    for (const PlotPoint& p : s.points) xs.push_back(p.x), ys.push_back(p.y);
  const Axis x(xs, plot.log_x), y(ys, plot.log_y, plot.y_from_zero);
  std::size_t drawable = 0, hidden = 0;
  for (const PlotSeries& s : plot.series)
    for (const PlotPoint& p : s.points) (x.drawable(p.x) && y.drawable(p.y) ? drawable : hidden) += 1;

  // Layout: the plot area, the legend to its right.
  const double left = 70, top = 34, legend_width = 290, bottom = 52;
  const double right = plot.width - legend_width, base = plot.height - bottom;
  auto px = [&](double v) { return svg_coordinate(x.pixel(v, left, right)); };
  auto py = [&](double v) { return svg_coordinate(y.pixel(v, base, top)); };

  std::string svg = "<svg class=\"plot\" id=\"" + escape(plot.id) + "\" xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"0 0 " +
                    std::to_string(plot.width) + " " + std::to_string(plot.height) + "\" width=\"" + std::to_string(plot.width) +
                    "\" height=\"" + std::to_string(plot.height) + "\" role=\"img\" aria-label=\"" + escape(plot.title) +
                    "\" data-points=\"" + std::to_string(drawable) + "\">\n";
  svg += "<text class=\"title\" x=\"" + svg_coordinate(left) + "\" y=\"20\">" + escape(plot.title) + "</text>\n";
  // Grid and tick labels.
  for (double t : x.ticks()) {
    svg += "<line class=\"grid\" x1=\"" + px(t) + "\" y1=\"" + svg_coordinate(top) + "\" x2=\"" + px(t) + "\" y2=\"" +
           svg_coordinate(base) + "\"/>";
    svg += "<text class=\"tick\" x=\"" + px(t) + "\" y=\"" + svg_coordinate(base + 16) + "\" text-anchor=\"middle\">" +
           escape(x.tick_label(t)) + "</text>\n";
  }
  for (double t : y.ticks()) {
    svg += "<line class=\"grid\" x1=\"" + svg_coordinate(left) + "\" y1=\"" + py(t) + "\" x2=\"" + svg_coordinate(right) +
           "\" y2=\"" + py(t) + "\"/>";
    svg += "<text class=\"tick\" x=\"" + svg_coordinate(left - 6) + "\" y=\"" + py(t) + "\" dy=\"4\" text-anchor=\"end\">" +
           escape(y.tick_label(t)) + "</text>\n";
  }
  svg += "<rect class=\"frame\" x=\"" + svg_coordinate(left) + "\" y=\"" + svg_coordinate(top) + "\" width=\"" +
         svg_coordinate(right - left) + "\" height=\"" + svg_coordinate(base - top) + "\"/>\n";
  svg += "<text class=\"axis-label\" x=\"" + svg_coordinate((left + right) / 2) + "\" y=\"" + svg_coordinate(base + 38) +
         "\" text-anchor=\"middle\">" + escape(plot.x_label + (x.logarithmic() ? " (log scale)" : "")) + "</text>\n";
  svg += "<text class=\"axis-label\" transform=\"translate(16 " + svg_coordinate((top + base) / 2) +
         ") rotate(-90)\" text-anchor=\"middle\">" + escape(plot.y_label + (y.logarithmic() ? " (log)" : "")) + "</text>\n";
  if (drawable == 0)
    svg += "<text class=\"empty\" x=\"" + svg_coordinate((left + right) / 2) + "\" y=\"" + svg_coordinate((top + base) / 2) +
           "\" text-anchor=\"middle\">no data in this report</text>\n";

  // Series, each in its colour; a legend entry per series.
  for (std::size_t k = 0; k < plot.series.size(); ++k) {
    const PlotSeries& s = plot.series[k];
    const std::string colour = s.colour.empty() ? series_colour(k) : s.colour;
    const std::string dash = " stroke-dasharray=\"" + (s.dash.empty() ? std::string("5 3") : s.dash) + "\"";
    svg += "<g class=\"series\" data-series=\"" + escape(s.name) + "\">";
    if (s.joined) {
      std::string points;
      for (const PlotPoint& p : s.points)
        if (x.drawable(p.x) && y.drawable(p.y)) points += (points.empty() ? "" : " ") + px(p.x) + "," + py(p.y);
      if (!points.empty())
        svg += "<polyline fill=\"none\" stroke=\"" + colour + "\" stroke-width=\"1.6\"" +
               (s.dashed ? dash : "") + " points=\"" + points + "\"/>";
    }
    if (s.markers)
      for (const PlotPoint& p : s.points) {
        if (!x.drawable(p.x) || !y.drawable(p.y)) continue;
        const std::string tip = p.label.empty() ? s.name + " (" + number(p.x, 4) + ", " + number(p.y, 4) + ")" : p.label;
        svg += "<circle cx=\"" + px(p.x) + "\" cy=\"" + py(p.y) + "\" r=\"3.5\" fill=\"" + colour + "\"><title>" + escape(tip) +
               "</title></circle>";
      }
    svg += "</g>\n";
    const double ly = top + 6 + 16.0 * double(k);
    svg += "<g class=\"legend\"><line x1=\"" + svg_coordinate(right + 12) + "\" y1=\"" + svg_coordinate(ly) + "\" x2=\"" +
           svg_coordinate(right + 30) + "\" y2=\"" + svg_coordinate(ly) + "\" stroke=\"" + colour + "\" stroke-width=\"3\"" +
           (s.dashed ? dash : "") + "/><text x=\"" + svg_coordinate(right + 36) + "\" y=\"" +
           svg_coordinate(ly + 4) + "\">" + escape(s.name) + "</text></g>\n";
  }
  svg += "</svg>\n";
  std::string note = plot.note;
  if (hidden > 0)
    note += (note.empty() ? "" : " ") + std::to_string(hidden) + " point" + (hidden == 1 ? "" : "s") +
            " not drawn (zero or negative on a logarithmic axis, or not a number).";
  if (!note.empty()) svg += "<p class=\"plot-note\">" + escape(note) + "</p>\n";
  return "<figure class=\"plot-figure\">\n" + svg + "</figure>\n";
}

}  // namespace cullcheck::html
