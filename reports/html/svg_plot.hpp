// Plots of the report page as inline SVG, written by cullcheck itself: no script library, so the
// page opens offline and the same report gives the same bytes. Scatter and line series on linear
// or logarithmic axes, a legend, a tooltip (<title>) on every marker.
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace cullcheck::html {

// One axis: the data range [lo, hi] widened to round ticks (1, 2, 5 x 10^k on a linear axis;
// decades on a logarithmic one), mapped onto the pixel span [from, to].
class Axis {
 public:
  // `values` are the data on this axis; non-finite values (and, on a log axis, values <= 0) are
  // ignored. With no usable value the axis spans [0, 1] (or [1, 10]).
  Axis(const std::vector<double>& values, bool logarithmic, bool include_zero = false);
  double lo() const { return lo_; }
  double hi() const { return hi_; }
  bool logarithmic() const { return log_; }
  const std::vector<double>& ticks() const { return ticks_; }
  // A tick's label: as many decimals as the tick step needs (20, 0.5, 0.25), decades as 1e5.
  std::string tick_label(double tick) const;
  // Whether v can be drawn on this axis (finite; positive on a log axis).
  bool drawable(double v) const;
  // The pixel of v, lo at `from` and hi at `to`.
  double pixel(double v, double from, double to) const;

 private:
  double lo_ = 0.0, hi_ = 1.0, step_ = 1.0;
  bool log_ = false;
  std::vector<double> ticks_;
};

struct PlotPoint {
  double x = 0.0, y = 0.0;
  std::string label;  // the marker's tooltip; empty: "series (x, y)"
  PlotPoint(double x_, double y_, std::string label_ = "") : x(x_), y(y_), label(std::move(label_)) {}
};

struct PlotSeries {
  std::string name;
  std::vector<PlotPoint> points;  // drawn in this order when joined
  bool joined = true;             // a line through the points
  bool markers = true;            // a circle at each point
  bool dashed = false;
  std::string colour;  // empty: series_colour of its place in the plot
  std::string dash;    // an SVG stroke-dasharray when dashed; empty: "5 3"
};

struct Plot {
  std::string id;  // the SVG element's id (the page's tests look plots up by it)
  std::string title, x_label, y_label;
  bool log_x = false, log_y = false;
  bool y_from_zero = false;  // a linear y axis that starts at 0
  std::vector<PlotSeries> series;
  std::string note;  // a line under the plot (what the axes mean, where the data came from)
  int width = 860, height = 380;
};

// The colour of the n-th series (a fixed palette told apart by colour-blind readers too).
std::string series_colour(std::size_t n);

// The plot as an <svg class="plot"> element. A plot without a drawable point says so in place of
// its data (an empty section, never a blank box); points an axis cannot show (<= 0 on a log axis)
// are left out and counted in the note.
std::string svg_plot(const Plot& plot);

}  // namespace cullcheck::html
